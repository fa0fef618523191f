#pragma once
// How long a test waits for something it expects before it gives up (issue 41). A wait polls its
// condition and returns as soon as it holds, so its limit costs a passing run nothing: the limit
// only turns a hang into a failure that says what never happened. So it is generous: ctest runs
// the suites side by side on machines shared with other builds, where work that takes a second
// alone can take minutes (a studio wait of 60 s ran out under a load of 15 on 2 cores).
// BHM_TEST_TIME_SCALE (a positive number, default 1) multiplies it for slower setups still
// (sanitizers, valgrind, emulation). Assertions on how long something took (a cancel within a
// second) and fixed observation windows (nothing moves for 1.5 s while paused) are not waits and
// do not use it.
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace bhm::test {

//! BHM_TEST_TIME_SCALE, 1 when unset; throws std::invalid_argument when it is not a positive
//! number (a typo must not silently shorten every wait).
inline double time_scale() {
    const char* text = std::getenv("BHM_TEST_TIME_SCALE");
    if (!text || !*text) return 1.0;
    char* end = nullptr;
    const double scale = std::strtod(text, &end);
    if (*end != '\0' || !(scale > 0.0))
        throw std::invalid_argument(std::string("BHM_TEST_TIME_SCALE='") + text +
                                    "': expected a positive number");
    return scale;
}

//! The limit of every wait in the suites: 5 minutes times time_scale(). At scale 1 that is half
//! the 600 s scripts/test.sh gives each test (ctest --timeout), so a hang fails with the test's
//! own message rather than ctest's kill; with a larger scale, raise ctest's --timeout to match.
inline double wait_limit_s() {
    return 300.0 * time_scale();
}

//! Calls between() (a frame, a short sleep) until done() holds or wait_limit_s() has passed;
//! whether done() held.
template <class Done, class Between>
bool wait_until(Done done, Between between) {
    const auto end =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_limit_s());
    while (!done()) {
        if (std::chrono::steady_clock::now() >= end) return done();
        between();
    }
    return true;
}

}  // namespace bhm::test
