// evolution.algorithm: "afpo" is the default (files without the field keep working), known names
// round-trip, anything else is refused with one line naming the file and the field.
#include <doctest/doctest.h>

#include <string>

#include "evo/experiment/experiment_io.hpp"
#include "evo_test_support.hpp"

using namespace bhm::evo;

TEST_CASE("evolution.algorithm defaults to afpo, round-trips, and rejects unknown names") {
    const auto base = test::tiny_experiment();
    auto json = experiment_to_json(base);
    CHECK(json["evolution"]["algorithm"] == "afpo");

    json["evolution"].erase("algorithm");  // an older file
    CHECK(parse_experiment(json, "old.json").evolution.algorithm == Algorithm::Afpo);

    json["evolution"]["algorithm"] = "afpo";
    CHECK(parse_experiment(json, "x.json") == base);

    json["evolution"]["algorithm"] = "genetic";
    try {
        parse_experiment(json, "exp.json");
        FAIL("an unknown algorithm was accepted");
    } catch (const ValidationError& e) {
        const std::string message = e.what();
        CHECK(message.find('\n') == std::string::npos);
        CHECK(message.rfind("exp.json:evolution.algorithm: 'genetic' is not one of", 0) == 0);
    }
    json["evolution"]["algorithm"] = 3;
    CHECK_THROWS_AS(parse_experiment(json, "exp.json"), ValidationError);
}
