// The message of the voxray::error a call throws: what the bad-input tests compare.
#pragma once
#include <exception>
#include <string>

#include <gtest/gtest.h>

#include "voxray/core/error.hpp"

namespace voxray::test {

// "" and a test failure when f throws nothing or something that is not a voxray::error.
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const error& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not a voxray::error: " << e.what();
        return "";
    }
    ADD_FAILURE() << "no voxray::error thrown";
    return "";
}

}  // namespace voxray::test
