// docs/studio.md's table of script steps is the script's own table (script_steps(), issue 39):
// a step added, renamed or reworded in app/gui/shell/script.cpp fails here until the document
// says the same. On a difference the test prints the table's text to paste in.
#include <doctest/doctest.h>

#include <string>

#include "app/gui/shell/script.hpp"
#include "engine/io/text_file.hpp"

namespace bhm::app::gui {

namespace {

// The Markdown table that starts at "| step | does |" in docs/studio.md, up to its last row.
std::string documented_steps() {
    const std::string doc = engine::read_text(std::string(BHM_SOURCE_DIR) + "/docs/studio.md");
    const auto start = doc.find("| step | does |\n");
    if (start == std::string::npos) return {};
    auto end = doc.find("\n\n", start);
    if (end == std::string::npos) end = doc.size();
    return doc.substr(start, end - start + 1);
}

}  // namespace

TEST_CASE("studio script: docs/studio.md lists every step as the script's table says") {
    const std::string generated = script_reference();
    INFO("docs/studio.md's table of steps (section Headless scripts) should read:\n" << generated);
    CHECK(documented_steps() == generated);
}

TEST_CASE("studio script: every step of the table has a handler, an example of its own kind, a help") {
    for (const ScriptStep& step : script_steps()) {
        INFO(step.name);
        CHECK(static_cast<bool>(step.run));
        CHECK(std::string(step.example).rfind(std::string("{\"") + step.name + "\"", 0) == 0);
        CHECK(std::string(step.help).size() > 3);
    }
}

TEST_CASE("studio script: a step of no known kind is refused with its text") {
    Studio studio;
    HeadlessStudio session(studio, 320, 240);
    CHECK_THROWS_WITH_AS(run_step(session, nlohmann::json::parse(R"({"jump": 1})")),
                         "unknown step {\"jump\":1}", ScriptError);
    CHECK_THROWS_AS(run_step(session, nlohmann::json::parse("{}")), ScriptError);
}

}  // namespace bhm::app::gui
