#include "evo/run/member_summary.hpp"

namespace bhm::evo {

MemberSummary summary_of(const Individual& m) {
    MemberSummary s;
    s.id = m.id;
    s.fitness = m.report.fitness;
    s.age = m.age;
    s.voxels = m.phenotype.voxels;
    s.active_voxels = m.phenotype.active_voxels;
    s.valid = m.valid;
    s.diverged = m.report.diverged;
    s.exploits = m.report.exploits;
    return s;
}

}  // namespace bhm::evo
