#pragma once
// Axis arithmetic for the fitness plot: auto-fitted ranges and round tick values (1, 2, 5 x 10^k).
#include <string>
#include <vector>

namespace bhm::app::gui {

struct AxisRange {
    double min = 0.0;
    double max = 1.0;
    double span() const { return max - min; }
};

//! The range of the finite values with `padding` (fraction of the span) on both sides; a single
//! value or none gets a unit-wide range around it (or [0, 1]).
AxisRange fit_range(const std::vector<double>& values, double padding = 0.05);

//! Round tick values inside [range.min, range.max], about `target` of them, step 1, 2 or 5 x 10^k.
std::vector<double> nice_ticks(const AxisRange& range, int target = 5);

//! Round ticks for an axis length_px long whose labels need min_gap_px each: about `most` of
//! them (never more than `most` + 1) when there is room, fewer on a short axis, so labels never overlap (issue 25 item 7:
//! plots squeezed to 30 px overlapped theirs). At least one tick for a non-empty range.
std::vector<double> spaced_ticks(const AxisRange& range, float length_px, float min_gap_px,
                                 int most);

//! A tick label with no more digits than the tick step needs ("0.25", "1200", "1e+06").
std::string format_tick(double value, double step);

//! Median of the values (the mean of the middle two for an even count); 0 for none.
double median_of(std::vector<double> values);

}  // namespace bhm::app::gui
