#pragma once
// Lattice operations on bodies that the evolution needs: connectivity, hashing, counting.
#include <cstdint>
#include <vector>

#include "evo/experiment/experiment.hpp"

namespace bhm::evo {

//! Face-connected component label per cell (-1 for empty cells). Components are numbered in the
//! order their first cell appears in index order (x fastest), so labels are deterministic.
std::vector<int> face_connected_labels(const Body& body, int* component_count = nullptr);

//! The body with only its largest face-connected component kept. Ties go to the component whose
//! first cell comes first in index order (x fastest, then y, then z).
Body largest_face_connected_component(const Body& body);

//! 64-bit FNV-1a of the size, the cells and (when any cell has its own) the fibre axes: the
//! phenotype's identity for the fitness cache and the neutral-mutation test. A collision (odds
//! ~1e-10 for a 2000-generation run) would reuse a result.
std::uint64_t hash_body(const Body& body);

int count_filled(const Body& body);
//! Cells whose material is active (cte > 0) in the experiment's palette.
int count_active(const Body& body, const std::vector<MaterialEntry>& materials);

}  // namespace bhm::evo
