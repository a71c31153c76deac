// One exception type for the whole library. Messages name the file, offset,
// limit or value that was wrong, so a user can act on them without a debugger.
#pragma once
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace voxray {

class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Builds a message from parts: fail("file ", path, ": offset ", off, " past end").
template <class... Parts>
[[noreturn]] inline void fail(Parts&&... parts) {
    std::ostringstream out;
    (out << ... << std::forward<Parts>(parts));
    throw error(out.str());
}

// Throws when a size or count goes past a documented limit.
template <class Value, class Limit>
inline void check_limit(const char* what, Value value, Limit limit) {
    if (value > limit) fail(what, " is ", value, ", above the limit of ", limit);
}

}  // namespace voxray
