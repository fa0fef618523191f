#pragma once
// The evolution's only source of randomness: xoshiro256** (Blackman & Vigna 2018) seeded through
// splitmix64. Its whole state is four words, saved in every checkpoint, so a resumed run draws the
// same numbers as one never interrupted. Never std::random_device or rand(): results must depend
// on the seed alone.
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace bhm::evo {

//! splitmix64 step: used to expand a 64-bit seed into the xoshiro state and to derive sub-seeds.
inline std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

class Rng {
  public:
    using State = std::array<std::uint64_t, 4>;

    explicit Rng(std::uint64_t seed = 1) {
        std::uint64_t s = seed;
        for (auto& word : state_)
            word = splitmix64(s);
    }

    //! Next raw 64-bit value (xoshiro256**).
    std::uint64_t next_u64() {
        const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
        const std::uint64_t t = state_[1] << 17;
        state_[2] ^= state_[0];
        state_[3] ^= state_[1];
        state_[1] ^= state_[2];
        state_[0] ^= state_[3];
        state_[2] ^= t;
        state_[3] = rotl(state_[3], 45);
        return result;
    }

    //! Uniform in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
    //! Uniform in [lo, hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

    //! Uniform integer in [lo, hi] (inclusive), without modulo bias (Lemire's rejection).
    int uniform_int(int lo, int hi) {
        const std::uint64_t range =
            static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo) + 1;
        const std::uint64_t limit = (0 - range) % range;  // 2^64 mod range
        std::uint64_t draw = next_u64();
        while (draw < limit)
            draw = next_u64();
        return static_cast<int>(static_cast<std::int64_t>(lo) +
                                static_cast<std::int64_t>(draw % range));
    }

    //! Index in [0, count); count must be > 0.
    int index(int count) { return uniform_int(0, count - 1); }

    //! Standard normal by Box-Muller; the second value is dropped so the state stays four words.
    double normal() {
        const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
        const double u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    }

    bool chance(double probability) { return uniform() < probability; }

    const State& state() const { return state_; }
    void set_state(const State& state) { state_ = state; }

  private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    State state_{};
};

}  // namespace bhm::evo
