// A calibration's batches of simulations elsewhere (bhm calibrate under mpirun, app/mpi/): the
// byte messages come back bit for bit, and a fit whose batches run in another order, through the
// messages and from a setup decoded as a rank decodes it, equals the fit on the worker pool. The
// MPI front end itself is checked under mpirun by tests/mpi/mpi_calibrate_test.sh.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "evo/calibrate/calibrator.hpp"
#include "evo/calibrate/track_batches.hpp"
#include "evo/calibrate/track_wire.hpp"
#include "evo/evaluate/evaluation_wire.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "test_support_calibrate.hpp"

using namespace bhm::evo;

namespace {

struct Setup {
    Experiment experiment = test::calibration_experiment();
    Body framed = apply_frame_and_overrides(experiment, test::bilayer(false));
    std::vector<FitParameter> parameters = parse_fit_list("E", experiment);
    MeasuredTrack track = test::synthetic_track(
        apply_fit(experiment, parameters, {std::log(1.25)}), framed, 0.005);
};

//! As a rank runs them: the setup and every job through their bytes, the batch backwards, each
//! result through its bytes.
class ThroughTheWire final : public TrackBatches {
  public:
    explicit ThroughTheWire(const TrackSetupMessage& setup)
        : remote_(decode_track_setup(encode_track_setup(setup))),
          parameters_(parse_fit_list(remote_.fit_list, remote_.experiment)) {}
    int batches = 0;
    void simulate(const TrackProblem&, const std::vector<std::vector<double>>& xs,
                  std::vector<SimulatedTrack>& results, const std::atomic<bool>* cancel,
                  const std::function<void(std::size_t, const SimulatedTrack&)>& on_result)
        override {
        ++batches;
        const TrackProblem mine{&remote_.experiment, &parameters_, &remote_.framed_body,
                                &remote_.track};
        results.assign(xs.size(), SimulatedTrack{});
        for (std::size_t k = xs.size(); k-- > 0;) {
            const TrackJobMessage job =
                decode_track_job(encode_track_job({7, static_cast<std::uint32_t>(k), xs[k]}));
            const TrackResultMessage r = decode_track_result(
                encode_track_result({job.batch, job.index, simulate_track_at(mine, job.x, cancel)}));
            results[r.index] = r.track;
            if (on_result) on_result(r.index, results[r.index]);
        }
    }
    int concurrency() const override { return 1; }

  private:
    TrackSetupMessage remote_;
    std::vector<FitParameter> parameters_;
};

}  // namespace

TEST_CASE("calibration messages come back bit for bit, and damaged ones are refused") {
    const Setup s;
    TrackSetupMessage setup{3, "E", s.experiment, s.framed, s.track};
    const TrackSetupMessage back = decode_track_setup(encode_track_setup(setup));
    CHECK(back.requested_threads == 3);
    CHECK(back.fit_list == "E");
    CHECK(back.experiment == s.experiment);
    CHECK(back.framed_body == s.framed);
    CHECK(back.track.t_s == s.track.t_s);
    REQUIRE(back.track.points.size() == 1);
    CHECK(back.track.points[0].name == "tip");
    CHECK(back.track.points[0].axes == s.track.points[0].axes);
    CHECK(back.track.points[0].position_m == s.track.points[0].position_m);

    const TrackJobMessage job{9, 4, {0.1 / 3.0, -1e-300}};
    const TrackJobMessage job_back = decode_track_job(encode_track_job(job));
    CHECK(job_back.batch == 9);
    CHECK(job_back.index == 4);
    CHECK(job_back.x == job.x);

    TrackResultMessage result{9, 4, simulate_track(FitPoint{s.experiment, 0.0}, s.framed, s.track)};
    result.track.diverged = true;
    result.track.divergence_reason = "a reason";
    const TrackResultMessage result_back = decode_track_result(encode_track_result(result));
    CHECK(result_back.track.position_m == result.track.position_m);
    CHECK(result_back.track.diverged);
    CHECK(result_back.track.divergence_reason == "a reason");
    CHECK(result_back.track.wall_s == result.track.wall_s);

    std::string bytes = encode_track_result(result);
    CHECK_THROWS_WITH_AS(decode_track_result(bytes.substr(0, bytes.size() - 3)),
                         doctest::Contains("truncated"), WireError);
    CHECK_THROWS_WITH_AS(decode_track_job(bytes), doctest::Contains("got message kind 3"),
                         WireError);
    bytes[4] = 9;  // another wire version
    CHECK_THROWS_WITH_AS(decode_track_result(bytes), doctest::Contains("same bhm build"),
                         WireError);
}

TEST_CASE("a fit whose batches run elsewhere, in another order, equals the worker pool's") {
    if (!calibration_available()) return;
    const Setup s;
    CalibrationOptions o;
    o.threads = 2;
    o.max_simulations = 12;
    const CalibrationResult pool = calibrate(s.experiment, s.framed, s.track, s.parameters, o);
    auto wire = std::make_shared<ThroughTheWire>(
        TrackSetupMessage{1, "E", s.experiment, s.framed, s.track});
    o.batches = wire;
    const CalibrationResult elsewhere = calibrate(s.experiment, s.framed, s.track, s.parameters, o);
    CHECK(wire->batches == 2);  // the scan and the Jacobian
    CHECK(elsewhere.x == pool.x);
    CHECK(elsewhere.misfit_after_m == pool.misfit_after_m);
    CHECK(elsewhere.fitted[0].value == pool.fitted[0].value);
    CHECK(elsewhere.fitted[0].sigma == pool.fitted[0].sigma);
    CHECK(elsewhere.after.position_m == pool.after.position_m);
    CHECK(elsewhere.optimiser_simulations == pool.optimiser_simulations);
    // The fit moved: the test compares a real search, not the starting point twice.
    CHECK(std::abs(pool.x[0]) > 0.05);
}
