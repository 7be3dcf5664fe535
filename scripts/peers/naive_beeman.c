/* The paper's chain, integrated as the paper writes Beeman's scheme, in the
 * plainest C: one peer of scripts/bench-peers.sh (not impact's code, not
 * tuned). The canonical bilayer (bottom layer: length 1 - x, modulus
 * 1 - alpha; top: x, alpha; density 1, impact speed 1) laid out as
 * crates/chain/src/layout.rs lays it out: masses in proportion to the
 * lengths, element 0 the wall spring (pushing only while compressed),
 * element j between masses j - 1 and j of the layer of mass j, the time step
 * min 2 pi sqrt(m/k) / 100.
 *
 *   cc -O3 -march=native -o naive_beeman naive_beeman.c -lm
 *   ./naive_beeman X ALPHA N STEPS     # prints "e loop_seconds"
 *
 * e is the centre of mass's velocity after STEPS steps over the impact
 * speed (as the LAMMPS peer reports it); loop_seconds times the steps only.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

int main(int argc, char **argv) {
    if (argc != 5) {
        fprintf(stderr, "usage: %s X ALPHA N STEPS\n", argv[0]);
        return 2;
    }
    double x = atof(argv[1]), alpha = atof(argv[2]);
    long n = atol(argv[3]), steps = atol(argv[4]);
    double length[2] = {1.0 - x, x}, modulus[2] = {1.0 - alpha, alpha};
    long count0 = lround(n * length[0]);
    if (count0 < 1 || count0 >= n) {
        fprintf(stderr, "choose x with N x whole and both layers present\n");
        return 2;
    }
    long count[2] = {count0, n - count0};
    double l0[2], k[2], m[2];
    for (int i = 0; i < 2; i++) {
        l0[i] = length[i] / count[i];
        k[i] = modulus[i] / l0[i];
        m[i] = l0[i]; /* density 1 */
    }
    double dt = fmin(2 * M_PI * sqrt(m[0] / k[0]) / 100, 2 * M_PI * sqrt(m[1] / k[1]) / 100);
    /* per mass: its spring below (element j) and its mass */
    double *ks = malloc(n * sizeof *ks), *inv_m = malloc(n * sizeof *inv_m);
    double *u = calloc(n, sizeof *u), *v = malloc(n * sizeof *v);
    double *a = calloc(n, sizeof *a), *a_prev = calloc(n, sizeof *a_prev), *a_new = malloc(n * sizeof *a_new);
    for (long j = 0; j < n; j++) {
        int layer = j < count0 ? 0 : 1;
        ks[j] = k[layer];
        inv_m[j] = 1.0 / m[layer];
        v[j] = -1.0;
    }
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (long s = 0; s < steps; s++) {
        for (long j = 0; j < n; j++)
            u[j] += dt * v[j] + dt * dt / 6.0 * (4.0 * a[j] - a_prev[j]);
        for (long j = 0; j < n; j++) {
            /* element j below mass j (the wall spring for j = 0, pushing
               only while compressed), element j + 1 above it */
            double below = j == 0 ? (u[0] < 0.0 ? -ks[0] * u[0] : 0.0) : ks[j] * (u[j - 1] - u[j]);
            double above = j + 1 < n ? ks[j + 1] * (u[j + 1] - u[j]) : 0.0;
            a_new[j] = (below + above) * inv_m[j];
        }
        for (long j = 0; j < n; j++) {
            v[j] += dt / 6.0 * (2.0 * a_new[j] + 5.0 * a[j] - a_prev[j]);
            a_prev[j] = a[j];
            a[j] = a_new[j];
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double momentum = 0.0, mass = 0.0;
    for (long j = 0; j < n; j++) {
        momentum += v[j] / inv_m[j];
        mass += 1.0 / inv_m[j];
    }
    printf("%.17g %.9g\n", momentum / mass, (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec));
    return 0;
}
