// ompl_peers: the C++ side of bench/compare.sh, built against Debian's libompl-dev.
//
//   ompl_peers prm MAP QUERIES PLANNER VERTICES RESOLUTION_M SEED OUT.json ROUTES.txt SIMPLIFY_S [VALIDATOR]
//   ompl_peers dubins PAIRS.bin RADIUS OUT.bin OUT.json [REPS]
//   ompl_peers validity MAP POINTS.txt OUT.json
//
// `prm` is in prm.cpp. `dubins` times DubinsStateSpace::distance over the shared pose pairs.
// `validity` compares this side's point test (Map::blocked, the state validity checker of
// `prm`) with skyroute's verdicts on the points `peers validity` wrote.
#include "common.hpp"
#include "map.hpp"

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/DubinsStateSpace.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <iostream>
#include <memory>

namespace ob = ompl::base;

namespace peers {
int run_prm(const std::vector<std::string> &args);

/// `dubins PAIRS.bin RADIUS OUT.bin OUT.json [REPS]`: the forward-only DubinsStateSpace's
/// `distance` (the shortest path's length) for every pair, REPS passes (default 5) timed;
/// writes the lengths (f64) and the ns per path of each pass.
static int run_dubins(const std::vector<std::string> &args) {
    if (args.size() < 4) {
        std::cerr << "dubins PAIRS.bin RADIUS OUT.bin OUT.json [REPS]\n";
        return 2;
    }
    const std::vector<double> v = read_f64(args[0]);
    const double radius = std::stod(args[1]);
    const int reps = args.size() > 4 ? std::stoi(args[4]) : 5;
    const std::size_t n = v.size() / 6;
    auto space = std::make_shared<ob::DubinsStateSpace>(radius, false);
    ob::ScopedState<ob::DubinsStateSpace> a(space), b(space);
    std::vector<double> ns;
    volatile double sink = 0;
    for (int r = 0; r < reps; ++r) {
        double sum = 0;
        const double t0 = now_s();
        for (std::size_t i = 0; i < n; ++i) {
            const double *p = &v[6 * i];
            a->setXY(p[0], p[1]);
            a->setYaw(p[2]);
            b->setXY(p[3], p[4]);
            b->setYaw(p[5]);
            sum += space->distance(a.get(), b.get());
        }
        ns.push_back((now_s() - t0) * 1e9 / double(n));
        sink = sum;
    }
    (void)sink;
    std::vector<double> lengths(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double *p = &v[6 * i];
        a->setXY(p[0], p[1]);
        a->setYaw(p[2]);
        b->setXY(p[3], p[4]);
        b->setYaw(p[5]);
        lengths[i] = space->distance(a.get(), b.get());
    }
    write_f64(args[2], lengths);
    std::vector<double> sorted = ns;
    std::sort(sorted.begin(), sorted.end());
    Obj o;
    o.add("solver", str("OMPL DubinsStateSpace::distance (f64, forward-only)"));
    o.add("pairs", double(n)).add("radius_m", radius).add("ns_per_path_passes", nums(ns));
    o.add("ns_per_path_median", sorted[(sorted.size() - 1) / 2]);
    write_text(args[3], o.done() + "\n");
    return 0;
}

/// `validity MAP POINTS.txt OUT.json`: reads `x y blocked distance` lines (skyroute's verdict
/// and distance, f32) and counts the points where Map::blocked disagrees; for those, records
/// how far skyroute's distance lies from the clearance (a disagreement within f32 rounding of
/// the contour is expected to be possible, one farther out is a bug in one of the checkers).
static int run_validity(const std::vector<std::string> &args) {
    if (args.size() < 3) {
        std::cerr << "validity MAP POINTS.txt OUT.json\n";
        return 2;
    }
    const Map map = Map::read(args[0]);
    std::ifstream in(args[1]);
    double x, y, theirs_d;
    int theirs;
    std::size_t n = 0, disagree = 0, blocked = 0;
    double worst = 0, worst_distance_diff = 0;
    while (in >> x >> y >> theirs >> theirs_d) {
        ++n;
        const bool ours = map.blocked(x, y);
        blocked += ours;
        const double d = map.distance(x, y);
        if (std::isfinite(d) && std::isfinite(theirs_d))
            worst_distance_diff = std::max(worst_distance_diff, std::abs(d - theirs_d));
        if (ours != (theirs != 0)) {
            ++disagree;
            worst = std::max(worst, std::abs(theirs_d - map.clearance));
        }
    }
    Obj o;
    o.add("points", double(n)).add("blocked_cpp", double(blocked)).add("disagreements", double(disagree));
    o.add("disagreement_max_offset_from_contour_m", worst);
    o.add("max_distance_difference_m", worst_distance_diff);
    write_text(args[2], o.done() + "\n");
    std::cerr << "validity: " << n << " points, " << disagree << " disagreements\n";
    return 0;
}

}  // namespace peers

int main(int argc, char **argv) {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    if (argc < 2) {
        std::cerr << "usage: ompl_peers prm|dubins|validity ARGS...\n";
        return 2;
    }
    const std::string cmd = argv[1];
    const std::vector<std::string> args(argv + 2, argv + argc);
    try {
        if (cmd == "prm") return peers::run_prm(args);
        if (cmd == "dubins") return peers::run_dubins(args);
        if (cmd == "validity") return peers::run_validity(args);
        std::cerr << "unknown command " << cmd << "\n";
        return 2;
    } catch (const std::exception &e) {
        std::cerr << "ompl_peers: " << e.what() << "\n";
        return 1;
    }
}
