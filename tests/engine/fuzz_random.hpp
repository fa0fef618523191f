#pragma once
// The envelope fuzzes' random numbers (test_engine_envelope*.cpp): SplitMix64, a fixed sequence
// on every platform (std:: distributions are not), so a seed names the same bodies everywhere.
#include <cstdint>

namespace bhm::engine::test {

struct Random {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

}  // namespace bhm::engine::test
