#include "evo/evaluate/tracks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/world.hpp"
#include "evo/evaluate/exploit_flags.hpp"

namespace bhm::evo {

namespace {

//! The face whose layer is the base of the bend: the first fixed face, x- if none is fixed.
Face bend_base_face(const Boundary& boundary) {
    for (int f = 0; f < 6; ++f)
        if (boundary.faces[static_cast<std::size_t>(f)] == BoundaryKind::Fixed)
            return static_cast<Face>(f);
    return Face::XMin;
}

}  // namespace

Vec3& TrackSample::track(int k) {
    return const_cast<Vec3&>(static_cast<const TrackSample&>(*this).track(k));
}

const Vec3& TrackSample::track(int k) const {
    switch (k) {
        case 0:
            return com_m;
        case 1:
            return bend_base_m;
        case 2:
            return bend_tip_m;
        case 3:
            return behaviour_tip_m;
        case 4:
            return exploit_base_m;
        case 5:
            return exploit_moving_m;
        case 6:
            return mass_moment;
        default:
            return thin_mass_moment;
    }
}

BendLayers bend_layers(const Experiment& experiment, const engine::World& world) {
    BendLayers layers;
    const auto& model = world.model();
    const Face face = bend_base_face(experiment.boundary);
    const auto axis = static_cast<std::size_t>(face) / 2;
    const bool base_on_high_side = static_cast<int>(face) % 2 == 1;
    const int n = model.voxel_count();
    if (n == 0) return layers;
    int lo = model.voxel_coords(0)[axis], hi = lo;
    for (int v = 1; v < n; ++v) {
        lo = std::min(lo, model.voxel_coords(v)[axis]);
        hi = std::max(hi, model.voxel_coords(v)[axis]);
    }
    if (lo == hi) return layers;  // one layer: no line to bend
    const int base_layer = base_on_high_side ? hi : lo;
    const int tip_layer = base_on_high_side ? lo : hi;
    for (int v = 0; v < n; ++v) {
        const int c = model.voxel_coords(v)[axis];
        if (c == base_layer) layers.base.push_back(v);
        if (c == tip_layer) layers.tip.push_back(v);
    }
    return layers;
}

ExploitGroups exploit_groups(const Experiment& experiment, const engine::World& world) {
    (void)experiment;  // the held voxels come from the model, which applied the boundary
    ExploitGroups g;
    const auto& model = world.model();
    const auto& spec = model.spec();
    Body body;
    body.size = {spec.nx, spec.ny, spec.nz};
    body.cells = spec.material;
    const BodyAnatomy a = body_anatomy(body, spec.fixed, false);
    const int count = model.voxel_count();
    const double volume = std::pow(model.voxel_size_m(), 3);
    g.mass_kg.resize(static_cast<std::size_t>(count));
    g.thin.resize(static_cast<std::size_t>(count));
    double base_s2 = 0.0, moving_s2 = 0.0;
    for (int v = 0; v < count; ++v) {
        const auto cell = static_cast<std::size_t>(model.voxel_cell(v));
        const int material = model.voxel_material(v);
        g.mass_kg[static_cast<std::size_t>(v)] =
            spec.materials[static_cast<std::size_t>(material - 1)].density_kg_m3 * volume;
        g.total_mass_kg += g.mass_kg[static_cast<std::size_t>(v)];
        g.thin[static_cast<std::size_t>(v)] = a.thin[cell];
        const int hop = a.hops[cell];
        if (hop < 1) continue;  // held, or unanchored (escaped covers those)
        const double s2 = static_cast<double>(hop) * hop;
        g.moving.push_back(v);
        moving_s2 += s2;
        if (hop <= kBaseHops) {
            g.base.push_back(v);
            base_s2 += s2;
        }
    }
    if (!g.base.empty()) g.base_mean_s2 = base_s2 / static_cast<double>(g.base.size());
    if (!g.moving.empty()) g.moving_mean_s2 = moving_s2 / static_cast<double>(g.moving.size());
    return g;
}

Vec3 centroid_of(const engine::World& world, const std::vector<int>& voxels) {
    Vec3 sum{0.0, 0.0, 0.0};
    if (voxels.empty()) return sum;
    for (int v : voxels) {
        const auto p = world.voxel_position_m(v);
        for (std::size_t k = 0; k < 3; ++k)
            sum[k] += p[k];
    }
    for (auto& s : sum)
        s /= static_cast<double>(voxels.size());
    return sum;
}

TrackSampler::TrackSampler(const Experiment& experiment, const engine::World& world)
    : settle_s_(experiment.simulation.settle_s),
      layers_(bend_layers(experiment, world)),
      behaviour_tip_(layers_.tip),
      groups_(exploit_groups(experiment, world)) {
    if (behaviour_tip_.empty()) {
        behaviour_tip_.resize(static_cast<std::size_t>(world.model().voxel_count()));
        std::iota(behaviour_tip_.begin(), behaviour_tip_.end(), 0);
    }
}

TrackSample TrackSampler::positions_of(const engine::World& world) const {
    TrackSample s;
    s.t_s = world.time_s();
    s.com_m = world.centre_of_mass_m();
    if (!layers_.base.empty() && !layers_.tip.empty()) {
        s.bend_base_m = centroid_of(world, layers_.base);
        s.bend_tip_m = centroid_of(world, layers_.tip);
    }
    s.behaviour_tip_m = centroid_of(world, behaviour_tip_);
    s.exploit_base_m = centroid_of(world, groups_.base);
    s.exploit_moving_m = centroid_of(world, groups_.moving);
    return s;
}

void TrackSampler::add_moments(const engine::World& world, TrackSample& s) const {
    const int count = world.model().voxel_count();
    for (int v = 0; v < count; ++v) {
        const auto i = static_cast<std::size_t>(v);
        const auto p = world.voxel_position_m(v);
        for (std::size_t k = 0; k < 3; ++k) {
            const double part = groups_.mass_kg[i] * (p[k] - reference_[i][k]);
            s.mass_moment[k] += part;
            if (groups_.thin[i]) s.thin_mass_moment[k] += part;
        }
    }
}

TrackSample TrackSampler::sample(const engine::World& world) {
    TrackSample s = positions_of(world);
    if (!settled(s.t_s, settle_s_)) return s;
    const int count = world.model().voxel_count();
    if (!has_reference_) {
        has_reference_ = true;
        reference_.resize(static_cast<std::size_t>(count));
        for (int v = 0; v < count; ++v)
            reference_[static_cast<std::size_t>(v)] = world.voxel_position_m(v);
        return s;  // both sums are zero at the reference
    }
    add_moments(world, s);
    return s;
}

void TrackSampler::before(const engine::World& world, double due_s) {
    before_ = positions_of(world);
    before_step_ = world.steps();
    if (has_reference_) {
        add_moments(world, before_);
    } else if (settled(due_s, settle_s_)) {
        // The next sample is the reference: its positions are interpolated too.
        const int count = world.model().voxel_count();
        before_positions_.resize(static_cast<std::size_t>(count));
        for (int v = 0; v < count; ++v)
            before_positions_[static_cast<std::size_t>(v)] = world.voxel_position_m(v);
    }
}

TrackSample TrackSampler::sample_at(const engine::World& world, double due_s) {
    const bool interpolate = before_step_ >= 0 && before_step_ + 1 == world.steps();
    const double t_after = world.time_s(), t_before = before_.t_s;
    // The weight of the step at or past due_s: 1 there (the sample is that step's, bit for bit),
    // 0 at the step before. a + f (b - a) keeps a track that does not move exactly constant (a
    // held layer's centroid: the settling test reads a spread of exactly 0 as at rest, and
    // (1 - f) a + f a can differ from a in the last bit).
    const double f =
        interpolate ? std::clamp((due_s - t_before) / (t_after - t_before), 0.0, 1.0) : 1.0;
    before_step_ = -1;
    TrackSample s = positions_of(world);
    s.t_s = due_s;
    if (settled(due_s, settle_s_)) {
        if (!has_reference_) {
            has_reference_ = true;
            const int count = world.model().voxel_count();
            const bool have_before =
                interpolate && before_positions_.size() == static_cast<std::size_t>(count);
            reference_.resize(static_cast<std::size_t>(count));
            for (int v = 0; v < count; ++v) {
                const auto i = static_cast<std::size_t>(v);
                const auto p = world.voxel_position_m(v);
                for (std::size_t k = 0; k < 3; ++k)
                    reference_[i][k] =
                        have_before ? before_positions_[i][k] + f * (p[k] - before_positions_[i][k])
                                    : p[k];
            }
            before_positions_.clear();
            before_positions_.shrink_to_fit();
        } else {
            add_moments(world, s);
        }
    }
    if (!interpolate || f == 1.0) return s;
    // Linear in time between the two steps (positions, and so every centroid and moment; the
    // mass moments of the reference sample stay zero: neither end has any).
    for (int t = 0; t < TrackSample::kTracks; ++t) {
        Vec3& x = s.track(t);
        const Vec3& a = before_.track(t);
        for (std::size_t c = 0; c < 3; ++c)
            x[c] = a[c] + f * (x[c] - a[c]);
    }
    return s;
}

double sample_due_s(std::int64_t k, double sample_period_s, double total_s, double dt_s) {
    const double due = static_cast<double>(k) * sample_period_s;
    return due >= total_s - 0.5 * dt_s ? total_s : due;
}

}  // namespace bhm::evo
