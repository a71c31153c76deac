// Seeded malformed-input generator: from a valid file and where its structure starts
// (chunk, field or line boundaries), every truncation at a boundary, deleted,
// duplicated and swapped segments (missing or repeated chunks, properties, lines),
// flipped bytes, huge/negative counts written over the words at each boundary, and for
// text formats numbers replaced by NaN, infinities, negatives and out-of-range values.
// Deterministic: the same sample and seed give the same mutants.
//
// A format is one input_format value (formats.hpp); run_malformed (malformed_run.hpp)
// feeds every mutant of every sample to the format's loader.
#pragma once
#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace voxray::test::malformed {

using bytes = std::vector<std::uint8_t>;

struct input_format {
    std::string name;                                                  // "vox", "obj", ...
    std::vector<bytes> samples;                                        // valid files; each must load
    std::function<void(const bytes&)> load;                            // loads, or throws voxray::error
    std::function<std::vector<std::size_t>(const bytes&)> boundaries;  // offsets where structure starts
    bool text = false;                                                 // also mutate number tokens
    std::function<void(bytes&)> reseal = {};  // e.g. recompute a checksum; mutants then run both ways
};

struct mutant {
    std::string what;  // e.g. "truncated at 120", "word 0xffffffff at 36"
    bytes data;
};

// splitmix64: small, seedable, the same on every platform.
struct mutation_rng {
    std::uint64_t s;
    std::uint64_t next() {
        std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    std::size_t below(std::size_t n) { return n ? std::size_t(next() % n) : 0; }
};

namespace detail {

inline void add(std::vector<mutant>& out, std::string what, bytes data) { out.push_back({std::move(what), std::move(data)}); }

inline bool is_number_char(std::uint8_t c) {
    return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E';
}

// [begin, end) of every whitespace-separated token that starts like a number.
inline std::vector<std::pair<std::size_t, std::size_t>> number_tokens(const bytes& b) {
    std::vector<std::pair<std::size_t, std::size_t>> out;
    for (std::size_t i = 0; i < b.size();) {
        if (b[i] == ' ' || b[i] == '\n' || b[i] == '\r' || b[i] == '\t' || b[i] == '/') { ++i; continue; }
        std::size_t j = i;
        while (j < b.size() && b[j] != ' ' && b[j] != '\n' && b[j] != '\r' && b[j] != '\t' && b[j] != '/') ++j;
        bool number = (b[i] >= '0' && b[i] <= '9') || ((b[i] == '-' || b[i] == '.') && j > i + 1);
        for (std::size_t k = i; number && k < j; ++k) number = is_number_char(b[k]);
        if (number) out.push_back({i, j});
        i = j;
    }
    return out;
}

}  // namespace detail

// Every mutant of `sample`. `limit` caps the seeded (random) part per kind.
inline std::vector<mutant> make_mutants(const input_format& f, const bytes& sample, std::uint64_t seed,
                                        std::size_t limit = 150) {
    using detail::add;
    std::vector<mutant> out;
    mutation_rng rng{seed};
    const std::size_t n = sample.size();
    std::vector<std::size_t> cuts = f.boundaries ? f.boundaries(sample) : std::vector<std::size_t>{};
    cuts.push_back(0);
    cuts.push_back(n);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    while (!cuts.empty() && cuts.back() > n) cuts.pop_back();

    // Truncation at, just before and just after every boundary.
    for (std::size_t c : cuts)
        for (std::size_t at : {c, c - 1, c + 1})
            if (at < n && (at == c || c > 0)) add(out, "truncated at " + std::to_string(at), bytes(sample.begin(), sample.begin() + std::ptrdiff_t(at)));

    // Segments between boundaries: missing, repeated, out of order.
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        auto a = std::ptrdiff_t(cuts[i]), b = std::ptrdiff_t(cuts[i + 1]);
        bytes del(sample.begin(), sample.begin() + a);
        del.insert(del.end(), sample.begin() + b, sample.end());
        add(out, "segment " + std::to_string(a) + ".." + std::to_string(b) + " deleted", del);
        bytes dup(sample.begin(), sample.begin() + b);
        dup.insert(dup.end(), sample.begin() + a, sample.end());
        add(out, "segment " + std::to_string(a) + ".." + std::to_string(b) + " repeated", dup);
        if (i + 2 < cuts.size()) {
            auto c = std::ptrdiff_t(cuts[i + 2]);
            bytes swap(sample.begin(), sample.begin() + a);
            swap.insert(swap.end(), sample.begin() + b, sample.begin() + c);
            swap.insert(swap.end(), sample.begin() + a, sample.begin() + b);
            swap.insert(swap.end(), sample.begin() + c, sample.end());
            add(out, "segments at " + std::to_string(a) + " and " + std::to_string(b) + " swapped", swap);
        }
    }

    // Counts and sizes: the 32-bit words at and after each boundary set to extremes,
    // and the 64-bit word at each boundary to huge values.
    static constexpr std::uint32_t words32[] = {0u, 1u, 0x7fffffffu, 0x80000000u, 0xffffffffu, 0x10000000u, 0xffffu};
    static constexpr std::uint64_t words64[] = {0xffffffffffffffffull, 0x8000000000000000ull, 0x100000000ull};
    for (std::size_t c : cuts)
        for (std::size_t off : {0u, 4u, 8u, 12u}) {
            std::size_t at = c + off;
            if (at + 4 > n) continue;
            for (std::uint32_t w : words32) {
                bytes m = sample;
                for (int k = 0; k < 4; ++k) m[at + k] = std::uint8_t(w >> (8 * k));
                add(out, "word " + std::to_string(w) + " at " + std::to_string(at), m);
            }
            if (off == 0 && at + 8 <= n)
                for (std::uint64_t w : words64) {
                    bytes m = sample;
                    for (int k = 0; k < 8; ++k) m[at + k] = std::uint8_t(w >> (8 * k));
                    add(out, "64-bit word " + std::to_string(w) + " at " + std::to_string(at), m);
                }
        }

    // Flipped bytes anywhere (one, or a burst of eight).
    for (std::size_t i = 0; i < limit && n; ++i) {
        bytes m = sample;
        std::size_t at = rng.below(n), count = i % 4 == 3 ? 8 : 1;
        for (std::size_t k = 0; k < count && at + k < n; ++k) {
            static constexpr std::uint8_t values[] = {0x00, 0xff, 0x80, 0x7f};
            auto r = rng.next();
            m[at + k] = r & 1 ? std::uint8_t(m[at + k] ^ (1u << (r >> 1) % 8)) : values[(r >> 1) % 4];
        }
        add(out, "bytes flipped at " + std::to_string(at), m);
    }

    // Text: numbers become NaN, infinities, negatives, too large for any type, or garbage.
    if (f.text) {
        static const char* replacements[] = {"nan", "-nan", "inf", "-inf", "1e400", "-1e400", "1e-400", "-1", "-0", "0",
                                             "2147483648", "-2147483649", "4294967296", "18446744073709551616",
                                             "99999999999999999999999999", "0x10", "1.5", "--1", "1e", "."};
        auto tokens = detail::number_tokens(sample);
        for (std::size_t i = 0; i < limit && !tokens.empty(); ++i) {
            auto [a, b] = tokens[rng.below(tokens.size())];
            std::string r = replacements[rng.below(std::size(replacements))];
            bytes m(sample.begin(), sample.begin() + std::ptrdiff_t(a));
            m.insert(m.end(), r.begin(), r.end());
            m.insert(m.end(), sample.begin() + std::ptrdiff_t(b), sample.end());
            add(out, "number at " + std::to_string(a) + " replaced by '" + r + "'", m);
        }
    }
    return out;
}

// Starts of lines (for text formats and text headers).
inline std::vector<std::size_t> line_starts(const bytes& b, std::size_t end = std::size_t(-1)) {
    std::vector<std::size_t> out{0};
    for (std::size_t i = 0; i < b.size() && i < end; ++i)
        if (b[i] == '\n') out.push_back(i + 1);
    return out;
}

}  // namespace voxray::test::malformed
