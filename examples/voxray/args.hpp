// A small command-line parser: positional arguments and --name value options, with
// clear errors for unknown options, missing values and malformed numbers.
#pragma once
#include <charconv>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "voxray/core/error.hpp"

namespace voxray::tool {

class args {
public:
    // `known` lists the options this subcommand accepts (without the dashes).
    args(int argc, char** argv, int first, std::set<std::string> known) {
        for (int i = first; i < argc; ++i) {
            std::string a = argv[i];
            if (a.rfind("--", 0) == 0) {
                std::string name = a.substr(2);
                if (!known.count(name)) fail("unknown option --", name);
                if (i + 1 >= argc) fail("option --", name, " needs a value");
                options_[name] = argv[++i];
            } else {
                positional_.push_back(a);
            }
        }
    }

    const std::vector<std::string>& positional() const { return positional_; }
    bool has(const std::string& name) const { return options_.count(name) != 0; }

    std::string get(const std::string& name, const std::string& fallback) const {
        auto it = options_.find(name);
        return it == options_.end() ? fallback : it->second;
    }

    // A whole number in [lo, hi].
    long long number(const std::string& name, long long fallback, long long lo, long long hi) const {
        auto it = options_.find(name);
        if (it == options_.end()) return fallback;
        long long v = 0;
        auto& s = it->second;
        auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (ec != std::errc() || end != s.data() + s.size()) fail("option --", name, ": '", s, "' is not a whole number");
        if (v < lo || v > hi) fail("option --", name, ": ", v, " is outside [", lo, ", ", hi, "]");
        return v;
    }

    // A comma-separated list.
    std::vector<std::string> list(const std::string& name, const std::string& fallback) const {
        std::vector<std::string> out;
        std::string s = get(name, fallback), item;
        for (char c : s + ",") {
            if (c == ',') {
                if (!item.empty()) out.push_back(item);
                item.clear();
            } else {
                item += c;
            }
        }
        return out;
    }

private:
    std::vector<std::string> positional_;
    std::map<std::string, std::string> options_;
};

}  // namespace voxray::tool
