/*
 * The C ABI from C: loads a network image, adds a circular pop-up, plans, and prints every
 * number the calls return in a plain text form; floats as C99 hex floats (%a), so the text
 * is bit-exact. ffi/tests/c_plan.rs runs the same calls through the Rust API and compares the
 * text (scripts/ffi-check.sh builds both and runs the comparison).
 *
 *   plan NETWORK.bin START_X START_Y START_HEADING GOAL_X GOAL_Y POPUP_X POPUP_Y POPUP_R
 *
 * Coordinates are metres in the network's local frame, headings radians counter-clockwise
 * from east; the goal's arrival heading is free. Numbers are read with strtof, which takes
 * hex floats. Exits 0 when every call returned what the sequence below expects of a network
 * on which the query has a route and the pop-up lies off the start and goal, 1 otherwise.
 */
#include "skyroute.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The planner's memory: a static block of the size and alignment the header guarantees. */
static _Alignas(SR_PLANNER_STORAGE_ALIGN) unsigned char planner_memory[SR_PLANNER_STORAGE_SIZE];

static int failures = 0;

/* Prints "LABEL status NAME" and counts a failure when the status is not the expected one. */
static void expect(const char *label, sr_status got, sr_status want) {
    printf("%s status %s\n", label, sr_status_name(got));
    if (got != want) {
        fprintf(stderr, "%s: %s, expected %s\n", label, sr_status_name(got), sr_status_name(want));
        failures++;
    }
}

static float parse_float(const char *s) {
    char *end = NULL;
    float v = strtof(s, &end);
    if (end == s || *end != '\0') {
        fprintf(stderr, "not a number: %s\n", s);
        exit(2);
    }
    return v;
}

/* The whole file, or NULL. It is never freed: the planner reads it in place. */
static uint8_t *read_file(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return NULL;
    }
    uint8_t *buf = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long size = ftell(f);
        if (size > 0 && fseek(f, 0, SEEK_SET) == 0) {
            buf = malloc((size_t)size);
            if (buf != NULL && fread(buf, 1, (size_t)size, f) == (size_t)size) {
                *len = (size_t)size;
            } else {
                free(buf);
                buf = NULL;
            }
        }
    }
    fclose(f);
    return buf;
}

static void print_summary(const sr_route_summary *s) {
    printf("summary length %a arrival_heading %a primitives %" PRIu32 " network_edges %" PRIu32
           "\n",
           s->length, s->arrival_heading, s->primitives, s->network_edges);
    printf("exit kind %u index %" PRIu32 " regions %" PRIu32 " length %a\n", s->exit_kind,
           s->exit_index, s->exit_regions, s->exit_length);
    const sr_work *w = &s->work;
    printf("work total %" PRIu64 " vertex_scans %" PRIu64 " dubins_solves %" PRIu64
           " collision_tests %" PRIu64 " heap_steps %" PRIu64 " relaxations %" PRIu64
           " cells_visited %" PRIu64 " threat_steps %" PRIu64 "\n",
           w->total, w->vertex_scans, w->dubins_solves, w->collision_tests, w->heap_steps,
           w->relaxations, w->cells_visited, w->threat_steps);
}

static void print_route(const sr_planner *planner) {
    static sr_primitive route[SR_MAX_ROUTE_PRIMITIVES];
    size_t count = 0;
    expect("route", sr_route_primitives(planner, route, SR_MAX_ROUTE_PRIMITIVES, &count),
           SR_STATUS_OK);
    for (size_t i = 0; i < count; i++) {
        const sr_primitive *p = &route[i];
        if (p->kind == SR_PRIMITIVE_LINE) {
            printf("line %zu %a %a %a %a\n", i, p->line.x0, p->line.y0, p->line.x1, p->line.y1);
        } else {
            printf("arc %zu %a %a %a %a %a\n", i, p->arc.cx, p->arc.cy, p->arc.radius,
                   p->arc.start_angle, p->arc.sweep);
        }
    }
}

/* Plans `query` with `budget`, expecting `want`; prints the summary and route on success. */
static void plan(sr_planner *planner, const char *label, const sr_query *query, uint64_t budget,
                 sr_status want) {
    sr_route_summary summary;
    memset(&summary, 0, sizeof summary);
    sr_status status = sr_plan(planner, query, budget, &summary);
    expect(label, status, want);
    if (status == SR_STATUS_OK) {
        print_summary(&summary);
        print_route(planner);
    }
}

int main(int argc, char **argv) {
    if (argc != 10) {
        fprintf(stderr, "usage: %s NETWORK.bin START_X START_Y START_HEADING GOAL_X GOAL_Y "
                        "POPUP_X POPUP_Y POPUP_R\n",
                argv[0]);
        return 2;
    }
    float v[8];
    for (int i = 0; i < 8; i++) {
        v[i] = parse_float(argv[i + 2]);
    }
    size_t len = 0;
    uint8_t *image = read_file(argv[1], &len);
    if (image == NULL) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }

    sr_planner *planner = NULL;
    printf("planner size %zu align %zu\n", sr_planner_size(), sr_planner_align());
    expect("init misaligned", sr_planner_init(planner_memory + 1, SR_PLANNER_STORAGE_SIZE - 1,
                                              &planner),
           SR_STATUS_MEMORY_MISALIGNED);
    expect("init too small", sr_planner_init(planner_memory, sr_planner_size() - 1, &planner),
           SR_STATUS_MEMORY_TOO_SMALL);
    expect("init", sr_planner_init(planner_memory, sizeof planner_memory, &planner),
           SR_STATUS_OK);
    if (planner == NULL) {
        return 1;
    }
    expect("load null", sr_load(planner, NULL, len), SR_STATUS_NULL_POINTER);
    expect("load truncated", sr_load(planner, image, 10), SR_STATUS_LOAD_TRUNCATED);
    expect("load", sr_load(planner, image, len), SR_STATUS_OK);
    uint32_t vertices = 0, edges = 0;
    expect("counts", sr_network_counts(planner, &vertices, &edges), SR_STATUS_OK);
    printf("network vertices %" PRIu32 " edges %" PRIu32 "\n", vertices, edges);

    uint64_t budget = 0, popup_work = 0;
    expect("worst case work", sr_worst_case_work(planner, &budget), SR_STATUS_OK);
    expect("worst case popup work", sr_worst_case_popup_work(planner, &popup_work),
           SR_STATUS_OK);
    printf("worst_case_work %" PRIu64 " popup %" PRIu64 "\n", budget, popup_work);

    sr_query query = {
        .start_x = v[0],
        .start_y = v[1],
        .start_heading = v[2],
        .goal_x = v[3],
        .goal_y = v[4],
        .goal_heading = 0.0f,
        .goal_has_heading = 0,
        .search = SR_SEARCH_DIJKSTRA,
    };
    plan(planner, "plan clear", &query, budget, SR_STATUS_OK);

    uint8_t id = 0xff;
    expect("popup zero radius", sr_add_popup_circle(planner, v[5], v[6], 0.0f, &id),
           SR_STATUS_POPUP_NON_POSITIVE_RADIUS);
    expect("popup", sr_add_popup_circle(planner, v[5], v[6], v[7], &id), SR_STATUS_OK);
    printf("popup id %u\n", id);
    plan(planner, "plan popup", &query, budget, SR_STATUS_OK);
    plan(planner, "plan popup a-star", &(sr_query){.start_x = v[0],
                                                   .start_y = v[1],
                                                   .start_heading = v[2],
                                                   .goal_x = v[3],
                                                   .goal_y = v[4],
                                                   .search = SR_SEARCH_A_STAR},
         budget, SR_STATUS_OK);
    plan(planner, "plan small budget", &query, 1000, SR_STATUS_PLAN_BUDGET_EXHAUSTED);
    sr_query inside = query;
    inside.goal_x = v[5];
    inside.goal_y = v[6];
    plan(planner, "plan goal in popup", &inside, budget, SR_STATUS_PLAN_INSIDE_POPUP);
    sr_query bad = query;
    bad.search = 7;
    plan(planner, "plan bad search", &bad, budget, SR_STATUS_INVALID_ARGUMENT);
    expect("plan null query", sr_plan(planner, NULL, budget, &(sr_route_summary){0}),
           SR_STATUS_NULL_POINTER);
    expect("plan null planner", sr_plan(NULL, &query, budget, &(sr_route_summary){0}),
           SR_STATUS_NULL_POINTER);

    expect("remove unknown", sr_remove_popup(planner, 9), SR_STATUS_POPUP_UNKNOWN_ID);
    expect("remove popups", sr_remove_popups(planner), SR_STATUS_OK);
    plan(planner, "plan cleared", &query, budget, SR_STATUS_OK);

    /* The start in latitude and longitude and back, then planned from the converted pose. */
    sr_pose null_planner_pose;
    expect("geo null planner", sr_geo_to_local(NULL, 0.0, 0.0, 0.0, &null_planner_pose),
           SR_STATUS_NULL_POINTER);
    sr_geo_pose geo;
    memset(&geo, 0, sizeof geo);
    expect("local to geo", sr_local_to_geo(planner, v[0], v[1], v[2], &geo), SR_STATUS_OK);
    printf("geo lon %a lat %a compass %a\n", geo.lon_deg, geo.lat_deg, geo.compass_deg);
    sr_pose pose;
    memset(&pose, 0, sizeof pose);
    expect("geo to local",
           sr_geo_to_local(planner, geo.lon_deg, geo.lat_deg, geo.compass_deg, &pose),
           SR_STATUS_OK);
    printf("local x %a y %a heading %a\n", (double)pose.x, (double)pose.y, (double)pose.heading);
    sr_query from_geo = query;
    from_geo.start_x = pose.x;
    from_geo.start_y = pose.y;
    from_geo.start_heading = pose.heading;
    plan(planner, "plan from geo", &from_geo, budget, SR_STATUS_OK);
    expect("geo latitude 91", sr_geo_to_local(planner, geo.lon_deg, 91.0, 0.0, &pose),
           SR_STATUS_GEO_LATITUDE);
    expect("geo heading nan", sr_geo_to_local(planner, geo.lon_deg, geo.lat_deg, NAN, &pose),
           SR_STATUS_GEO_NON_FINITE);
    expect("geo far east", sr_geo_to_local(planner, geo.lon_deg + 90.0, geo.lat_deg, 0.0, &pose),
           SR_STATUS_GEO_OUT_OF_FRAME);
    expect("geo null out", sr_local_to_geo(planner, v[0], v[1], v[2], NULL),
           SR_STATUS_NULL_POINTER);

    printf("failures %d\n", failures);
    return failures == 0 ? 0 : 1;
}
