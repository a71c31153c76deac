// Issue 12: the malformed-input generators run in the tests. Every mutant of every
// sample of every format (formats.hpp) must load or throw voxray::error with a message:
// no other exception, no crash or sanitizer report (this runs in the ASan+UBSan pass),
// and no more memory than a bound proportional to the input. Hangs meet ctest's timeout.
#include <cstdio>
#include <exception>
#include <string>
#include <typeinfo>
#include <vector>

#include <gtest/gtest.h>

#include "alloc_meter.hpp"
#include "formats.hpp"
#include "mutations.hpp"

namespace voxray::test::malformed {
namespace {

// What a mutant of n bytes may allocate at once: a generous constant for the loaders'
// fixed tables, plus a large factor of the input (a voxel each byte, a chunk each voxel).
std::size_t memory_bound(std::size_t n) { return (std::size_t(64) << 20) + 4096 * n; }

struct outcome {
    std::size_t loaded = 0, rejected = 0;
};

// Loads one input; records a failure with the format, the mutant and the problem.
void expect_load_or_error(const input_format& f, const mutant& m, outcome& o) {
    reset_peak();
    std::size_t before = live_bytes();
    try {
        f.load(m.data);
        ++o.loaded;
    } catch (const voxray::error& e) {
        ++o.rejected;
        EXPECT_GT(std::string(e.what()).size(), 10u) << f.name << ", " << m.what << ": an empty message";
    } catch (const std::exception& e) {
        ADD_FAILURE() << f.name << ", " << m.what << ": threw " << typeid(e).name() << ": " << e.what();
    } catch (...) {
        ADD_FAILURE() << f.name << ", " << m.what << ": threw something that is not a std::exception";
    }
    EXPECT_LE(peak_bytes() - before, memory_bound(m.data.size()))
        << f.name << ", " << m.what << ": " << m.data.size() << " bytes of input took " << peak_bytes() - before
        << " bytes of memory";
}

void run_format(const input_format& f) {
    ASSERT_FALSE(f.samples.empty()) << f.name;
    outcome o;
    std::size_t count = 0;
    for (std::size_t s = 0; s < f.samples.size(); ++s) {
        const bytes& sample = f.samples[s];
        ASSERT_NO_THROW(f.load(sample)) << f.name << " sample " << s << " must load";
        for (auto& m : make_mutants(f, sample, 1000 * s + 17)) {
            expect_load_or_error(f, m, o);
            ++count;
            if (f.reseal) {
                mutant sealed{m.what + ", resealed", m.data};
                f.reseal(sealed.data);
                expect_load_or_error(f, sealed, o);
                ++count;
            }
            if (::testing::Test::HasFailure()) return;  // the first failure says enough
        }
    }
    std::printf("[%s] %zu mutants of %zu samples: %zu loaded, %zu rejected\n", f.name.c_str(), count,
                f.samples.size(), o.loaded, o.rejected);
    // A generator that never reaches the loader's checks would prove nothing.
    EXPECT_GT(o.rejected, count / 4) << f.name;
}

class malformed_inputs : public ::testing::TestWithParam<input_format> {};

TEST_P(malformed_inputs, every_mutant_loads_or_throws_voxray_error) { run_format(GetParam()); }

INSTANTIATE_TEST_SUITE_P(formats, malformed_inputs, ::testing::ValuesIn(all_formats()),
                         [](const auto& info) { return info.param.name; });

// The generator itself: deterministic, and it covers what it says.
TEST(mutation_generator, is_deterministic_and_covers_each_kind) {
    auto f = vox_format();
    auto a = make_mutants(f, f.samples[0], 5), b = make_mutants(f, f.samples[0], 5);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i].data, b[i].data) << a[i].what;
    auto has = [&](const char* kind) {
        for (auto& m : a)
            if (m.what.find(kind) != std::string::npos) return true;
        return false;
    };
    for (const char* kind : {"truncated", "deleted", "repeated", "swapped", "word", "flipped"}) EXPECT_TRUE(has(kind)) << kind;
    auto obj = obj_format();
    bool nan = false;
    for (auto& m : make_mutants(obj, obj.samples[0], 5)) nan |= m.what.find("'nan'") != std::string::npos;
    EXPECT_TRUE(nan);
}

// The memory check can fail: a loader that allocated this much for a small input would.
TEST(alloc_meter, sees_a_large_allocation) {
    reset_peak();
    std::size_t before = live_bytes();
    // Through a volatile pointer: clang may elide a new whose result is not used.
    void* (*volatile allocate)(std::size_t) = static_cast<void* (*)(std::size_t)>(::operator new);
    void* big = allocate(memory_bound(100) + 1);
    ::operator delete(big);
    EXPECT_GT(peak_bytes() - before, memory_bound(100));
    EXPECT_EQ(live_bytes(), before);
}

}  // namespace
}  // namespace voxray::test::malformed
