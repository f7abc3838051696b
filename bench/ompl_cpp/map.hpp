// The map the C++ side plans on: the obstacles, clearance, turn radius and sampled area that
// `peers map` (bench/peers) writes from a skyroute network, and the exact point test.
#pragma once

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace peers {

/// A point in the network's local frame, metres.
struct P2 {
    double x, y;
};

/// The obstacles and limits of one network, in f64.
struct Map {
    double radius = 0, clearance = 0;
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the sampled area (the vertices' bounding box)
    std::vector<std::vector<P2>> polygons;
    std::vector<P2> lo, hi;                  // each polygon's bounding box
    struct Circle {
        double x, y, r;
    };
    std::vector<Circle> circles;

    /// A uniform grid over the area (and 500 m around it): for each cell, the polygons whose
    /// bounding box grown by the clearance overlaps it, the only ones that can block a point
    /// in the cell. It only narrows which polygons `blocked` tests exactly.
    double gx0 = 0, gy0 = 0, cell = 20.0;
    std::size_t nx = 0, ny = 0;
    std::vector<std::vector<std::size_t>> cells;

    void build_grid() {
        const double margin = 500.0;
        gx0 = x0 - margin;
        gy0 = y0 - margin;
        nx = static_cast<std::size_t>(std::ceil((x1 - x0 + 2 * margin) / cell));
        ny = static_cast<std::size_t>(std::ceil((y1 - y0 + 2 * margin) / cell));
        cells.assign(nx * ny, {});
        auto clampi = [](double v, std::size_t n) {
            return static_cast<std::size_t>(std::clamp(v, 0.0, double(n - 1)));
        };
        for (std::size_t i = 0; i < polygons.size(); ++i) {
            const std::size_t ia = clampi(std::floor((lo[i].x - clearance - gx0) / cell), nx);
            const std::size_t ib = clampi(std::floor((hi[i].x + clearance - gx0) / cell), nx);
            const std::size_t ja = clampi(std::floor((lo[i].y - clearance - gy0) / cell), ny);
            const std::size_t jb = clampi(std::floor((hi[i].y + clearance - gy0) / cell), ny);
            for (std::size_t j = ja; j <= jb; ++j)
                for (std::size_t k = ia; k <= ib; ++k) cells[j * nx + k].push_back(i);
        }
    }

    /// Reads the text written by `peers map` (format in bench/peers/src/world.rs).
    static Map read(const std::string &path) {
        std::ifstream in(path);
        if (!in) throw std::runtime_error(path + ": cannot open");
        Map m;
        std::string word;
        std::size_t n = 0;
        in >> word >> m.radius >> word >> m.clearance;
        in >> word >> m.x0 >> m.y0 >> m.x1 >> m.y1;
        in >> word >> n;
        for (std::size_t i = 0; i < n; ++i) {
            std::size_t k = 0;
            in >> k;
            std::vector<P2> poly(k);
            P2 a{1e300, 1e300}, b{-1e300, -1e300};
            for (auto &p : poly) {
                in >> p.x >> p.y;
                a = {std::min(a.x, p.x), std::min(a.y, p.y)};
                b = {std::max(b.x, p.x), std::max(b.y, p.y)};
            }
            m.polygons.push_back(poly);
            m.lo.push_back(a);
            m.hi.push_back(b);
        }
        in >> word >> n;
        for (std::size_t i = 0; i < n; ++i) {
            Circle c{};
            in >> c.x >> c.y >> c.r;
            m.circles.push_back(c);
        }
        if (!in) throw std::runtime_error(path + ": malformed map");
        m.build_grid();
        return m;
    }

    /// Distance from (x, y) to segment a-b.
    static double segment_distance(double x, double y, const P2 &a, const P2 &b) {
        const double dx = b.x - a.x, dy = b.y - a.y;
        const double len2 = dx * dx + dy * dy;
        double t = len2 > 0 ? ((x - a.x) * dx + (y - a.y) * dy) / len2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        return std::hypot(x - (a.x + t * dx), y - (a.y + t * dy));
    }

    /// Even-odd point-in-polygon test.
    static bool inside(double x, double y, const std::vector<P2> &poly) {
        bool in = false;
        for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
            const P2 &a = poly[i], &b = poly[j];
            if ((a.y > y) != (b.y > y)) {
                const double xc = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                if (x < xc) in = !in;
            }
        }
        return in;
    }

    /// Distance from (x, y) to obstacle polygon i (0 inside).
    double polygon_distance(double x, double y, std::size_t i) const {
        const auto &poly = polygons[i];
        if (inside(x, y, poly)) return 0.0;
        double d = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < poly.size(); ++k)
            d = std::min(d, segment_distance(x, y, poly[k], poly[(k + 1) % poly.size()]));
        return d;
    }

    /// Distance from (x, y) to the nearest obstacle (0 inside one). A polygon whose bounding
    /// box is farther than the nearest distance found so far is skipped (the box's distance is
    /// a lower bound of the polygon's).
    double distance(double x, double y) const {
        double d = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < polygons.size(); ++i) {
            const double bx = std::max({lo[i].x - x, 0.0, x - hi[i].x});
            const double by = std::max({lo[i].y - y, 0.0, y - hi[i].y});
            if (std::hypot(bx, by) >= d) continue;
            d = std::min(d, polygon_distance(x, y, i));
        }
        for (const auto &c : circles) d = std::min(d, std::max(std::hypot(x - c.x, y - c.y) - c.r, 0.0));
        return d;
    }

    /// Whether polygon i, inflated by the clearance, contains (x, y): its box grown by the
    /// clearance contains the point and its exact distance is at most the clearance.
    bool blocked_by(double x, double y, std::size_t i) const {
        const double c = clearance;
        if (x < lo[i].x - c || x > hi[i].x + c || y < lo[i].y - c || y > hi[i].y + c) return false;
        return polygon_distance(x, y, i) <= c;
    }

    /// Whether (x, y) lies inside a polygon inflated by the clearance (distance <= clearance,
    /// the polygon's interior included) or within radius + clearance of a circle. Inside the
    /// grid only the cell's polygons are tested; outside it, every polygon.
    bool blocked(double x, double y) const {
        const double fx = std::floor((x - gx0) / cell), fy = std::floor((y - gy0) / cell);
        if (fx >= 0 && fy >= 0 && fx < double(nx) && fy < double(ny)) {
            for (std::size_t i : cells[static_cast<std::size_t>(fy) * nx + static_cast<std::size_t>(fx)])
                if (blocked_by(x, y, i)) return true;
        } else {
            for (std::size_t i = 0; i < polygons.size(); ++i)
                if (blocked_by(x, y, i)) return true;
        }
        for (const auto &k : circles)
            if (std::hypot(x - k.x, y - k.y) <= k.r + clearance) return true;
        return false;
    }
};

}  // namespace peers
