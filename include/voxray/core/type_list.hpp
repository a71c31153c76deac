// A list of types, and a call of f.template operator()<T>() for each: how the tool and the
// tests walk every registered structure (voxray/generated/structures.hpp) or backend.
#pragma once

namespace voxray {

template <class... T>
struct type_list {};

template <class... T, class F>
void for_each_type(type_list<T...>, F&& f) {
    (f.template operator()<T>(), ...);
}

}  // namespace voxray
