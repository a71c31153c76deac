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

// Test names from a type's own name (T::name: a backend's or a structure's), with
// characters gtest dislikes replaced ("cpu-scalar" -> "cpu_scalar").
struct type_names {
    template <class T>
    static std::string GetName(int) {
        std::string s(T::name);
        for (char& c : s)
            if (c == '-') c = '_';
        return s;
    }
};

// Test names: "<structure>_on_<backend>", with characters gtest dislikes replaced.
struct case_names {
    template <class Case>
    static std::string GetName(int) {
        std::string s = std::string(Case::structure::name) + "_on_" + Case::backend::name;
        for (char& c : s)
            if (c == '-') c = '_';
        return s;
    }
};

}  // namespace voxray::test
