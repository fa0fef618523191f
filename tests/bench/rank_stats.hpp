#pragma once
// The statistics of bench_controllers (issue 44), written here rather than taken from SciPy
// (scripts/setup.sh installs no SciPy): a mean's 95 % Student t interval, the Mann-Whitney U test
// of two samples (two-sided; exact without ties, else the normal approximation with the tie
// correction and a continuity correction of 1/2) and the Kruskal-Wallis H test of k samples (tie
// corrected; p from the chi-square distribution with k - 1 degrees of freedom, in closed form
// for k = 2 and 3, the cases the benchmark uses).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>
#include <vector>

namespace bhm::bench {

inline double sample_mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v)
        s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

inline double sample_sd(const std::vector<double>& v) {
    if (v.size() < 2) return 0.0;
    const double m = sample_mean(v);
    double s = 0.0;
    for (double x : v)
        s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
}

//! The 0.975 quantile of Student's t with df degrees of freedom (tabulated to 3 decimals for
//! 1..30, then 40, 60, 120 and the normal's 1.960; between them the next smaller df's, which is
//! conservative).
inline double t_975(int df) {
    static const double table[30] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306,
                                     2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
                                     2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
                                     2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
    if (df < 1) throw std::invalid_argument("t quantile: df must be >= 1");
    if (df <= 30) return table[df - 1];
    if (df < 40) return 2.042;
    if (df < 60) return 2.021;
    if (df < 120) return 2.000;
    return 1.980;
}

//! Half the width of the mean's 95 % t interval (0 for fewer than two values).
inline double ci95_half_width(const std::vector<double>& v) {
    if (v.size() < 2) return 0.0;
    return t_975(static_cast<int>(v.size()) - 1) * sample_sd(v) /
           std::sqrt(static_cast<double>(v.size()));
}

//! Mid-ranks (1-based) of the values of all samples pooled; ties share their mean rank. Also the
//! tie correction sum of (t^3 - t) over groups of t equal values.
struct PooledRanks {
    std::vector<std::vector<double>> ranks;  //!< per sample, per value
    double tie_sum = 0.0;
    std::size_t total = 0;
};
inline PooledRanks pooled_ranks(const std::vector<std::vector<double>>& samples) {
    std::vector<std::pair<double, std::pair<std::size_t, std::size_t>>> all;
    PooledRanks out;
    out.ranks.resize(samples.size());
    for (std::size_t s = 0; s < samples.size(); ++s) {
        out.ranks[s].resize(samples[s].size());
        for (std::size_t i = 0; i < samples[s].size(); ++i)
            all.push_back({samples[s][i], {s, i}});
    }
    std::sort(all.begin(), all.end());
    out.total = all.size();
    for (std::size_t i = 0; i < all.size();) {
        std::size_t j = i;
        while (j < all.size() && all[j].first == all[i].first)
            ++j;
        const double rank = 0.5 * static_cast<double>(i + 1 + j);  // mean of ranks i+1 .. j
        for (std::size_t k = i; k < j; ++k)
            out.ranks[all[k].second.first][all[k].second.second] = rank;
        const double t = static_cast<double>(j - i);
        out.tie_sum += t * t * t - t;
        i = j;
    }
    return out;
}

struct RankTest {
    double statistic = 0.0;  //!< U of the first sample (Mann-Whitney) or H (Kruskal-Wallis)
    double p = 1.0;          //!< two-sided (Mann-Whitney); upper tail (Kruskal-Wallis)
    bool exact = false;      //!< Mann-Whitney: p from the exact distribution of U
};

//! Number of arrangements of m x-values and n y-values with U = u (pairs x > y), for u = 0..mn:
//! the recursion c(u; m, n) = c(u - n; m - 1, n) + c(u; m, n - 1) (the largest value an x or a y).
inline std::vector<double> u_counts(int m, int n) {
    // table[i][j] = counts for i x-values and j y-values.
    std::vector<std::vector<std::vector<double>>> table(
        static_cast<std::size_t>(m + 1),
        std::vector<std::vector<double>>(static_cast<std::size_t>(n + 1)));
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j) {
            auto& c = table[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
            c.assign(static_cast<std::size_t>(i * j + 1), 0.0);
            if (i == 0 || j == 0) {
                c[0] = 1.0;
                continue;
            }
            const auto& a = table[static_cast<std::size_t>(i - 1)][static_cast<std::size_t>(j)];
            const auto& b = table[static_cast<std::size_t>(i)][static_cast<std::size_t>(j - 1)];
            for (std::size_t u = 0; u < c.size(); ++u) {
                if (u >= static_cast<std::size_t>(j) && u - static_cast<std::size_t>(j) < a.size())
                    c[u] += a[u - static_cast<std::size_t>(j)];
                if (u < b.size()) c[u] += b[u];
            }
        }
    return table[static_cast<std::size_t>(m)][static_cast<std::size_t>(n)];
}

//! Two-sided Mann-Whitney U test of x against y. U = pairs with x > y plus half the ties.
inline RankTest mann_whitney(const std::vector<double>& x, const std::vector<double>& y) {
    if (x.empty() || y.empty()) throw std::invalid_argument("Mann-Whitney: an empty sample");
    const PooledRanks r = pooled_ranks({x, y});
    const double m = static_cast<double>(x.size()), n = static_cast<double>(y.size());
    double rank_sum = 0.0;
    for (double v : r.ranks[0])
        rank_sum += v;
    RankTest t;
    t.statistic = rank_sum - m * (m + 1.0) / 2.0;
    const double mean_u = m * n / 2.0;
    if (r.tie_sum == 0.0 && x.size() * y.size() <= 2500) {
        const auto c = u_counts(static_cast<int>(x.size()), static_cast<int>(y.size()));
        double total = 0.0, tail = 0.0;
        const double low = std::min(t.statistic, m * n - t.statistic);  // the nearer tail
        for (std::size_t u = 0; u < c.size(); ++u) {
            total += c[u];
            if (static_cast<double>(u) <= low + 1e-9) tail += c[u];
        }
        t.p = std::min(1.0, 2.0 * tail / total);
        t.exact = true;
        return t;
    }
    const double N = m + n;
    const double var = m * n / 12.0 * ((N + 1.0) - r.tie_sum / (N * (N - 1.0)));
    if (var <= 0.0) return t;  // every value equal: no evidence either way
    const double z = std::max(0.0, std::fabs(t.statistic - mean_u) - 0.5) / std::sqrt(var);
    t.p = std::min(1.0, std::erfc(z / std::sqrt(2.0)));
    return t;
}

//! Kruskal-Wallis H test of k = 2 or 3 samples (chi-square upper tail: erfc(sqrt(H/2)) for one
//! degree of freedom, exp(-H/2) for two).
inline RankTest kruskal_wallis(const std::vector<std::vector<double>>& samples) {
    const std::size_t k = samples.size();
    if (k < 2 || k > 3) throw std::invalid_argument("Kruskal-Wallis: 2 or 3 samples");
    const PooledRanks r = pooled_ranks(samples);
    const double N = static_cast<double>(r.total);
    double h = 0.0;
    for (const auto& ranks : r.ranks) {
        if (ranks.empty()) throw std::invalid_argument("Kruskal-Wallis: an empty sample");
        double s = 0.0;
        for (double v : ranks)
            s += v;
        h += s * s / static_cast<double>(ranks.size());
    }
    h = 12.0 / (N * (N + 1.0)) * h - 3.0 * (N + 1.0);
    const double correction = 1.0 - r.tie_sum / (N * N * N - N);
    RankTest t;
    if (correction <= 0.0) return t;  // every value equal
    t.statistic = h / correction;
    t.p = k == 2 ? std::erfc(std::sqrt(t.statistic / 2.0)) : std::exp(-t.statistic / 2.0);
    return t;
}

}  // namespace bhm::bench
