// Small helpers shared by the C++ side: the clock, reading the query and pose-pair files, and
// writing JSON by hand (numbers and flat objects only).
#pragma once

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace peers {

/// Seconds on a monotonic clock.
inline double now_s() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

/// The queries written by `peers queries`: one `sx sy sh gx gy gh` line each.
inline std::vector<std::array<double, 6>> read_queries(const std::string &path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::vector<std::array<double, 6>> out;
    std::array<double, 6> q{};
    while (in >> q[0] >> q[1] >> q[2] >> q[3] >> q[4] >> q[5]) out.push_back(q);
    return out;
}

/// The pose pairs written by `peers pairs`: little-endian f64, six per pair.
inline std::vector<double> read_f64(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<double> out(bytes.size() / sizeof(double));
    std::copy(bytes.begin(), bytes.begin() + out.size() * sizeof(double), reinterpret_cast<char *>(out.data()));
    return out;
}

/// Writes `values` as little-endian f64 (the x86-64 byte order).
inline void write_f64(const std::string &path, const std::vector<double> &values) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char *>(values.data()), values.size() * sizeof(double));
    if (!out) throw std::runtime_error(path + ": cannot write");
}

/// A JSON number (`null` for NaN and infinities), with round-trip precision.
inline std::string num(double x) {
    if (!std::isfinite(x)) return "null";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

/// A JSON string (the strings written here need no escaping).
inline std::string str(const std::string &s) { return "\"" + s + "\""; }

/// A JSON array of numbers.
inline std::string nums(const std::vector<double> &xs) {
    std::string s = "[";
    for (std::size_t i = 0; i < xs.size(); ++i) s += (i ? "," : "") + num(xs[i]);
    return s + "]";
}

/// Builds one flat JSON object, key by key.
class Obj {
public:
    Obj &add(const std::string &key, const std::string &json) {
        body_ += (body_.empty() ? "" : ", ") + str(key) + ": " + json;
        return *this;
    }
    Obj &add(const std::string &key, double x) { return add(key, num(x)); }
    Obj &flag(const std::string &key, bool b) { return add(key, std::string(b ? "true" : "false")); }
    std::string done() const { return "{" + body_ + "}"; }

private:
    std::string body_;
};

/// Writes `text` to `path`.
inline void write_text(const std::string &path, const std::string &text) {
    std::ofstream out(path);
    out << text;
    if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace peers
