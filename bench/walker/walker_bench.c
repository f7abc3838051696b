/*
 * walker_bench: Andrew Walker's dubins.c (the PyPI `dubins` sdist's dubins/src/dubins.c, which
 * bench/compare.sh downloads and compiles beside this file; it is not in the repository) over
 * the pose pairs of `peers pairs`.
 *
 *   walker_bench PAIRS.bin RADIUS OUT.bin OUT.json [REPS]
 *
 * Times dubins_shortest_path + dubins_path_length for every pair, REPS passes (default 5), and
 * writes each length as a little-endian f64 (NaN where the library returns an error) and the
 * ns per path of every pass.
 */
#include "dubins.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double length_of(double *q0, double *q1, double rho) {
    DubinsPath path;
    if (dubins_shortest_path(&path, q0, q1, rho) != 0) return NAN;
    return dubins_path_length(&path);
}

static int cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv) {
    if (argc < 5) {
        fprintf(stderr, "usage: walker_bench PAIRS.bin RADIUS OUT.bin OUT.json [REPS]\n");
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (!f) { perror(argv[1]); return 1; }
    fseek(f, 0, SEEK_END);
    long bytes = ftell(f);
    fseek(f, 0, SEEK_SET);
    size_t n = (size_t)bytes / (6 * sizeof(double));
    double *v = malloc(n * 6 * sizeof(double));
    double *lengths = malloc(n * sizeof(double));
    if (!v || !lengths || fread(v, sizeof(double), n * 6, f) != n * 6) { fprintf(stderr, "read failed\n"); return 1; }
    fclose(f);
    double rho = atof(argv[2]);
    int reps = argc > 5 ? atoi(argv[5]) : 5;
    double *ns = malloc((size_t)reps * sizeof(double));
    volatile double sink = 0;
    for (int r = 0; r < reps; ++r) {
        double sum = 0, t0 = now_s();
        for (size_t i = 0; i < n; ++i) {
            double l = length_of(&v[6 * i], &v[6 * i + 3], rho);
            if (l == l) sum += l;
        }
        ns[r] = (now_s() - t0) * 1e9 / (double)n;
        sink = sum;
    }
    (void)sink;
    for (size_t i = 0; i < n; ++i) lengths[i] = length_of(&v[6 * i], &v[6 * i + 3], rho);
    FILE *o = fopen(argv[3], "wb");
    if (!o || fwrite(lengths, sizeof(double), n, o) != n) { perror(argv[3]); return 1; }
    fclose(o);
    FILE *j = fopen(argv[4], "w");
    if (!j) { perror(argv[4]); return 1; }
    fprintf(j, "{\"solver\": \"Walker dubins.c (f64)\", \"pairs\": %zu, \"radius_m\": %.17g, \"ns_per_path_passes\": [", n, rho);
    for (int r = 0; r < reps; ++r) fprintf(j, "%s%.6g", r ? "," : "", ns[r]);
    qsort(ns, (size_t)reps, sizeof(double), cmp);
    fprintf(j, "], \"ns_per_path_median\": %.6g}\n", ns[(reps - 1) / 2]);
    fclose(j);
    return 0;
}
