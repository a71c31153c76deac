// A list of types, and a call of f.template operator()<T>() for each: how the tool and the
// tests walk every registered structure (voxray/generated/structures.hpp) or backend.
#pragma once

namespace voxray {

template <class... T>
struct type_list {};

// The types of several lists, in order, as one list.
template <class... Lists>
struct concat_type_lists;
template <>
struct concat_type_lists<> {
    using type = type_list<>;
};
template <class... A>
struct concat_type_lists<type_list<A...>> {
    using type = type_list<A...>;
};
template <class... A, class... B, class... Rest>
struct concat_type_lists<type_list<A...>, type_list<B...>, Rest...> : concat_type_lists<type_list<A..., B...>, Rest...> {};
template <class... Lists>
using concat_type_lists_t = typename concat_type_lists<Lists...>::type;

template <class... T, class F>
void for_each_type(type_list<T...>, F&& f) {
    (f.template operator()<T>(), ...);
}

}  // namespace voxray
