// OMPL's PRM* and LazyPRM over a forward-only DubinsStateSpace on a skyroute map: roadmap
// construction to a given vertex count, then one query per start/goal pair on that roadmap.
#include "common.hpp"
#include "map.hpp"

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/DubinsStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>

#include <atomic>
#include <utility>
#include <iostream>
#include <memory>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace peers {

/// A state is valid when its position is not blocked (Map::blocked: outside every polygon
/// inflated by the clearance). Counts its calls.
class MapValidity : public ob::StateValidityChecker {
public:
    MapValidity(const ob::SpaceInformationPtr &si, const Map &map) : ob::StateValidityChecker(si), map_(map) {}
    bool isValid(const ob::State *s) const override {
        checks.fetch_add(1, std::memory_order_relaxed);
        const auto *st = s->as<ob::SE2StateSpace::StateType>();
        return !map_.blocked(st->getX(), st->getY());
    }
    mutable std::atomic<unsigned long> checks{0};

private:
    const Map &map_;
};

/// LazyPRM with a way to grow its roadmap to a vertex count: the sampling step of
/// LazyPRM::solve (a uniform sample added as a milestone, joined to its neighbours without
/// any check) without the solution attempts, which need a query.
class GrowLazyPRM : public og::LazyPRM {
public:
    using og::LazyPRM::LazyPRM;
    void grow(std::size_t milestones) {
        ob::State *work = si_->allocState();
        while (milestoneCount() < milestones) {
            sampler_->sampleUniform(work);
            addMilestone(si_->cloneState(work));
        }
        si_->freeState(work);
    }
    /// Sampling iterations of solve() so far.
    unsigned long iterations() const { return iterations_; }
};

/// The Dubins word OMPL chose for a motion, e.g. "LSR".
static std::string word(const ob::DubinsStateSpace::DubinsPath &p) {
    std::string w;
    for (int i = 0; i < 3; ++i)
        w += p.type_[i] == ob::DubinsStateSpace::DUBINS_LEFT ? 'L'
             : p.type_[i] == ob::DubinsStateSpace::DUBINS_RIGHT ? 'R'
                                                               : 'S';
    return w;
}

/// What a route's dense check found: the smallest obstacle distance of its points every `step`
/// metres along every motion as flown (OMPL's own interpolation), and how many are blocked.
struct Dense {
    double min_distance = std::numeric_limits<double>::infinity();
    std::size_t blocked = 0;
};

static Dense dense_check(const ob::SpaceInformationPtr &si, const Map &map, const og::PathGeometric &path,
                         double step) {
    Dense d;
    ob::State *tmp = si->allocState();
    for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
        const ob::State *a = path.getState(i), *b = path.getState(i + 1);
        const auto n = static_cast<std::size_t>(std::ceil(si->distance(a, b) / step));
        for (std::size_t j = 0; j <= n; ++j) {
            si->getStateSpace()->interpolate(a, b, n ? double(j) / n : 0.0, tmp);
            const auto *st = tmp->as<ob::SE2StateSpace::StateType>();
            const double dist = map.distance(st->getX(), st->getY());
            d.min_distance = std::min(d.min_distance, dist);
            if (dist <= map.clearance) ++d.blocked;
        }
    }
    si->freeState(tmp);
    return d;
}

/// Appends a route to the routes file: `route QUERY PLANNER KIND MOTIONS`, then one line per
/// motion with its start state, OMPL's word and the piece lengths in metres.
static void write_route(std::ostringstream &out, const ob::DubinsStateSpace &space, double radius,
                        std::size_t q, const std::string &planner, const std::string &kind,
                        const og::PathGeometric &path) {
    out << "route " << q << ' ' << planner << ' ' << kind << ' ' << path.getStateCount() - 1 << '\n';
    out.precision(17);
    for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
        const auto *a = path.getState(i)->as<ob::SE2StateSpace::StateType>();
        const auto p = space.dubins(path.getState(i), path.getState(i + 1));
        out << a->getX() << ' ' << a->getY() << ' ' << a->getYaw() << ' ' << word(p);
        for (double l : p.length_) out << ' ' << l * radius;
        out << '\n';
    }
}

/// Motions of `path` that OMPL's own motion validator rejects in the direction of flight, and
/// how many of those it accepts the other way round (the Dubins path from the later state to
/// the earlier one, a different path in a forward-only space).
static std::pair<std::size_t, std::size_t> rejected_motions(const ob::SpaceInformationPtr &si,
                                                            const og::PathGeometric &path) {
    std::size_t bad = 0, valid_reversed = 0;
    for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
        if (!si->checkMotion(path.getState(i), path.getState(i + 1))) {
            ++bad;
            if (si->checkMotion(path.getState(i + 1), path.getState(i))) ++valid_reversed;
        }
    return {bad, valid_reversed};
}

/// `prm MAP QUERIES PLANNER VERTICES RESOLUTION_M SEED OUT.json ROUTES.txt SIMPLIFY_S [VALIDATOR]`
///
/// PLANNER is `prmstar` or `lazyprm`; VALIDATOR the motion validator, `discrete` (OMPL's
/// DiscreteMotionValidator, the default) or `dubins` (its DubinsMotionValidator), both
/// checking one state every RESOLUTION_M metres along the motion's Dubins path. Grows the roadmap to VERTICES milestones (PRM*:
/// `growRoadmap`, valid samples joined to their k nearest by checked motions; LazyPRM: uniform
/// samples joined to their neighbours unchecked), then answers every query on it:
/// * PRM*: `solve` with a termination condition that is already true. PRM adds start and goal
///   as milestones joined to their k nearest (checked motions), grows nothing, and returns the
///   A* route to the goal as its approximate solution; a route that ends at the goal counts.
/// * LazyPRM: `solve` stopped after one sampling iteration. LazyPRM adds start and goal
///   (unchecked edges), samples one milestone, and if start and goal share a component runs
///   A* and checks the route's vertices and edges, removing what fails, until a route passes
///   or they no longer share a component.
/// Each raw route is then simplified (`PathSimplifier::simplify`, SIMPLIFY_S cap), checked by
/// OMPL's motion validator in its direction of flight and densely (0.1 m), and written to
/// ROUTES.txt for the exact check with skyroute's predicates (`peers check`).
int run_prm(const std::vector<std::string> &args) {
    if (args.size() < 9) {
        std::cerr << "prm MAP QUERIES PLANNER VERTICES RESOLUTION_M SEED OUT.json ROUTES.txt SIMPLIFY_S [VALIDATOR]\n";
        return 2;
    }
    const Map map = Map::read(args[0]);
    const auto queries = read_queries(args[1]);
    const std::string name = args[2];
    const std::size_t vertices = std::stoul(args[3]);
    const double resolution_m = std::stod(args[4]);
    const double simplify_s = std::stod(args[8]);
    const std::string validator = args.size() > 9 ? args[9] : "discrete";
    ompl::RNG::setSeed(std::stoul(args[5]));

    // isSymmetric = false: distance and interpolate use the Dubins path from -> to, flown
    // forwards (only a symmetric space sets DubinsPath::reverse_ and flies a motion backwards),
    // so every route is flyable by a forward-only aircraft; what can fail is the clearance.
    auto space = std::make_shared<ob::DubinsStateSpace>(map.radius, false);
    ob::RealVectorBounds bounds(2);
    bounds.setLow(0, map.x0);
    bounds.setHigh(0, map.x1);
    bounds.setLow(1, map.y0);
    bounds.setHigh(1, map.y1);
    space->setBounds(bounds);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto validity = std::make_shared<MapValidity>(si, map);
    si->setStateValidityChecker(validity);
    if (validator == "discrete")
        si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
    else if (validator == "dubins")
        si->setMotionValidator(std::make_shared<ob::DubinsMotionValidator>(si));
    else
        throw std::runtime_error("unknown motion validator " + validator);
    si->setStateValidityCheckingResolution(resolution_m / space->getMaximumExtent());
    si->setup();

    std::shared_ptr<og::PRMstar> prm;
    std::shared_ptr<GrowLazyPRM> lazy;
    ob::PlannerPtr planner;
    if (name == "prmstar")
        planner = prm = std::make_shared<og::PRMstar>(si);
    else if (name == "lazyprm")
        planner = lazy = std::make_shared<GrowLazyPRM>(si);
    else
        throw std::runtime_error("unknown planner " + name);
    planner->setProblemDefinition(std::make_shared<ob::ProblemDefinition>(si));
    planner->setup();

    const double t0 = now_s();
    if (prm)
        prm->growRoadmap(ob::PlannerTerminationCondition([&] { return prm->milestoneCount() >= vertices; }));
    else
        lazy->grow(vertices);
    const double build_s = now_s() - t0;
    const unsigned long build_checks = validity->checks.load();
    auto milestones = [&] { return prm ? prm->milestoneCount() : lazy->milestoneCount(); };
    auto edges = [&] { return prm ? prm->edgeCount() : lazy->edgeCount(); };
    const double built_milestones = milestones(), built_edges = edges();

    std::string rows;
    std::ostringstream routes;
    og::PathSimplifier simplifier(si);
    for (std::size_t q = 0; q < queries.size(); ++q) {
        const auto &v = queries[q];
        ob::ScopedState<ob::DubinsStateSpace> start(space), goal(space);
        start->setXY(v[0], v[1]);
        start->setYaw(v[2]);
        goal->setXY(v[3], v[4]);
        goal->setYaw(v[5]);
        auto pdef = std::make_shared<ob::ProblemDefinition>(si);
        pdef->setStartAndGoalStates(start, goal);
        planner->setProblemDefinition(pdef);
        const unsigned long checks0 = validity->checks.load();
        const unsigned long iter0 = lazy ? lazy->iterations() : 0;
        ob::PlannerTerminationCondition ptc([&] {
            return prm ? true : lazy->iterations() >= iter0 + 1;
        });
        const double ts = now_s();
        const ob::PlannerStatus status = planner->solve(ptc);
        const double solve_s = now_s() - ts;
        const unsigned long query_checks = validity->checks.load() - checks0;

        Obj row;
        row.add("query", double(q)).add("status", str(status.asString())).add("solve_s", solve_s);
        row.add("state_checks", double(query_checks));
        bool solved = false;
        if (pdef->hasSolution()) {
            auto raw = *pdef->getSolutionPath()->as<og::PathGeometric>();
            const ob::State *last = raw.getState(raw.getStateCount() - 1);
            solved = space->equalStates(last, goal.get());
            if (solved) {
                og::PathGeometric simple(raw);
                const double tsim = now_s();
                simplifier.simplify(simple, simplify_s);
                const double simplify_time = now_s() - tsim;
                const Dense draw = dense_check(si, map, raw, 0.1), dsim = dense_check(si, map, simple, 0.1);
                row.add("raw_length_m", raw.length()).add("raw_states", double(raw.getStateCount()));
                row.add("simplified_length_m", simple.length()).add("simplify_s", simplify_time);
                const auto rraw = rejected_motions(si, raw), rsim = rejected_motions(si, simple);
                row.add("raw_rejected_motions", double(rraw.first));
                row.add("raw_rejected_motions_valid_reversed", double(rraw.second));
                row.add("simplified_rejected_motions", double(rsim.first));
                row.add("simplified_rejected_motions_valid_reversed", double(rsim.second));
                row.add("raw_dense_blocked_points", double(draw.blocked));
                row.add("raw_dense_min_distance_m", draw.min_distance);
                row.add("simplified_dense_blocked_points", double(dsim.blocked));
                row.add("simplified_dense_min_distance_m", dsim.min_distance);
                write_route(routes, *space, map.radius, q, name, "raw", raw);
                write_route(routes, *space, map.radius, q, name, "simplified", simple);
            }
        }
        row.flag("solved", solved);
        rows += (rows.empty() ? "\n  " : ",\n  ") + row.done();
        planner->clearQuery();
    }

    Obj top;
    top.add("planner", str(planner->getName())).add("vertices_target", double(vertices));
    top.add("milestones", built_milestones).add("edges", built_edges).add("build_s", build_s);
    top.add("build_state_checks", double(build_checks)).add("resolution_m", resolution_m);
    top.add("motion_validator", str(validator));
    top.add("longest_valid_segment_fraction", si->getStateValidityCheckingResolution());
    top.add("maximum_extent_m", space->getMaximumExtent()).add("simplify_cap_s", simplify_s);
    top.add("milestones_after_queries", double(milestones()));
    top.add("range_m", prm ? std::nan("") : lazy->getRange());
    top.add("queries", "[" + rows + "\n]");
    write_text(args[6], top.done() + "\n");
    write_text(args[7], routes.str());
    std::cerr << planner->getName() << ": " << built_milestones << " milestones, " << built_edges
              << " edges in " << build_s << " s\n";
    return 0;
}

}  // namespace peers
