#pragma once
// The rules between fields of an experiment (max_hidden_nodes >= min_hidden_nodes, a frame of a
// passive material, the step budget, ...), each declared once: the fields whose tooltip states
// it, the text the tooltip shows, and the check validate_experiment runs. A field's own range is
// the field table's (experiment_fields.hpp); a rule is what no single field can say.
#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "evo/experiment/experiment.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::evo {

//! What a rule's check is given: the experiment, and the problems found so far, to add to.
struct RuleCheck {
    const Experiment& experiment;
    const std::string& file;
    std::vector<Problem>& problems;
    void bad(const std::string& field, const std::string& message) const {
        problems.push_back({file, field, message});
    }
    //! True when a problem already names `field` (a rule does not report a field twice).
    bool reported(std::string_view field) const;
};

struct FieldRule {
    //! The fields whose tooltip states the rule: a table path ("evolution.cppn.max_hidden_nodes"),
    //! "materials[]." + a material field's key, or a path ending in '.' for every field under
    //! it; nullptr for none (a rule on the boundary's overrides or the materials list).
    std::array<const char*, 2> fields{};
    std::string (*text)() = nullptr;            //!< the rule as the tooltip says it
    void (*check)(const RuleCheck&) = nullptr;  //!< reports each break, naming its field
};

//! Every rule, in the order validate_experiment reports them (the step budget last: it is only
//! checked once everything it depends on is valid).
std::span<const FieldRule> field_rules();
//! The texts of the rules on the field at `path` ("materials[].cte_per_c" for a material's
//! field), joined by "; "; "" when none.
std::string rules_text(std::string_view path);
//! Appends every break of every rule to problems.
void check_rules(const Experiment& experiment, const std::string& file,
                 std::vector<Problem>& problems);

}  // namespace bhm::evo
