// Typed-test cases from type lists: every backend x every registered structure, as the
// ::testing::Types<...> a typed test suite is instantiated with, and readable names for
// them ("brickmap_on_cpu_scalar") instead of gtest's bare indices.
#pragma once
#include <string>

#include <gtest/gtest.h>

#include "voxray/core/type_list.hpp"

namespace voxray::test {

template <class Backend, class Structure>
struct trace_case {
    using backend = Backend;
    using structure = Structure;
};

// type_list<trace_case<B, S>...> for every B in Backends and S in Structures.
template <class Backends, class Structures>
struct cross;
template <class... B, class Structures>
struct cross<type_list<B...>, Structures> {
    template <class One, class List>
    struct with;
    template <class One, class... S>
    struct with<One, type_list<S...>> {
        using type = type_list<trace_case<One, S>...>;
    };
    using type = concat_type_lists_t<typename with<B, Structures>::type...>;
};

template <class List>
struct gtest_types;
template <class... T>
struct gtest_types<type_list<T...>> {
    using type = ::testing::Types<T...>;
};

// ::testing::Types<trace_case<B, S>...> over backends B... and every S of Structures.
template <class Structures, class... Backends>
using cases_t = typename gtest_types<typename cross<type_list<Backends...>, Structures>::type>::type;

// `s` with the characters gtest dislikes in a test name replaced ("cpu-scalar" -> "cpu_scalar").
inline std::string gtest_identifier(std::string s) {
    for (char& c : s)
        if (c == '-') c = '_';
    return s;
}

// Test names from a type's own name (T::name: a backend's or a structure's).
struct type_names {
    template <class T>
    static std::string GetName(int) {
        return gtest_identifier(std::string(T::name));
    }
};

// Test names: "<structure>_on_<backend>", with characters gtest dislikes replaced.
struct case_names {
    template <class Case>
    static std::string GetName(int) {
        return gtest_identifier(std::string(Case::structure::name) + "_on_" + Case::backend::name);
    }
};

}  // namespace voxray::test
