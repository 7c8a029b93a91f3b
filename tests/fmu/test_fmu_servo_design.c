/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The ServoDrive's design routines (fmu/servo_design.c) against closed forms:
 * - the matrix exponential of a damped rotation (e^{s t} [[cos, sin], [-sin, cos]]), of a double
 *   integrator's ZOH ([[1, T, T^2/2], [0, 1, T], [0, 0, 1]]) and of a badly scaled companion
 *   matrix (its eigenvectors, a Vandermonde matrix, diagonalise it);
 * - pole placement on a companion-form system, whose gain is the difference of the
 *   characteristic polynomials' coefficients, for real poles, complex pairs, a pole on an open
 *   loop eigenvalue (its limit) and a repeated pole (refused);
 * - the Riccati equation of a scalar system (a quadratic's root), a matrix one's residual, and
 *   a mode the input cannot stabilise (refused);
 * - the powers of stable, unstable, marginal and non-normal matrices (bounds and the radius).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "servo_design.h"
#include "../c/check.h"

#define U (DBL_EPSILON / 2.0)

static double max_abs(const double *a, int n)
{
    double m = 0.0;
    int i;
    for (i = 0; i < n; ++i)
        m = fabs(a[i]) > m ? fabs(a[i]) : m;
    return m;
}

static void test_expm(void)
{
    /* Damped rotation, ||M|| = 130: eight squarings. For a normal matrix the scaling and
     * squaring's error is about u ||M|| relative (Higham, "Functions of Matrices", 10.3). */
    const double s = -50.0, w = 80.0;
    double M[4] = { s, w, -w, s }, E[4], e = exp(s);
    double want[4];
    double A[9] = { 0.0, 2e-3, 0.0, 0.0, 0.0, 2e-3, 0.0, 0.0, 0.0 }, Z[9];
    int i;
    want[0] = want[3] = e * cos(w);
    want[1] = e * sin(w);
    want[2] = -want[1];
    CHECK(sd_expm(2, M, E) == 0);
    for (i = 0; i < 4; ++i)
        CHECK_CLOSE(E[i], want[i], 4.0 * 130.0 * U, e);
    /* ZOH of the double integrator with T = 2e-3: exact polynomials (a nilpotent M) */
    CHECK(sd_expm(3, A, Z) == 0);
    CHECK(Z[0] == 1.0 && Z[4] == 1.0 && Z[8] == 1.0 && Z[3] == 0.0 && Z[6] == 0.0 && Z[7] == 0.0);
    CHECK_CLOSE(Z[1], 2e-3, 4.0 * U, 2e-3);
    CHECK_CLOSE(Z[2], 2e-6, 4.0 * U, 2e-6);
    CHECK_CLOSE(Z[5], 2e-3, 4.0 * U, 2e-3);
    /* Companion matrix of (s + 1)(s + 10)(s + 100)(s + 1000) times 1e-3: last row 1e6 times its
     * ones before balancing (the reference model's shape). e^M = V diag(e^l) V^-1, V the
     * Vandermonde matrix of the roots; its condition (about 1e3 here) bounds the check. */
    {
        const double l[4] = { -1e-3, -1e-2, -0.1, -1.0 };
        double C[16] = { 0 }, V[16], D[16], EV[16], R[16], poly[5] = { 1, 0, 0, 0, 0 };
        int j, k;
        for (k = 0; k < 4; ++k)           /* poly = prod (s - l_k), highest power first */
            for (j = k + 1; j > 0; --j)
                poly[j] -= l[k] * poly[j - 1];
        for (i = 0; i < 3; ++i)
            C[i * 4 + i + 1] = 1.0;
        for (j = 0; j < 4; ++j)
            C[12 + j] = -poly[4 - j];
        for (i = 0; i < 4; ++i)           /* V[i][k] = l_k^i: columns are eigenvectors */
            for (k = 0; k < 4; ++k)
                V[i * 4 + k] = pow(l[k], i);
        CHECK(sd_expm(4, C, EV) == 0);
        /* E V = V diag(e^l) */
        sd_mul(4, 4, 4, EV, V, R);
        for (i = 0; i < 4; ++i)
            for (k = 0; k < 4; ++k)
                D[i * 4 + k] = V[i * 4 + k] * exp(l[k]);
        for (i = 0; i < 16; ++i)
            CHECK_CLOSE(R[i], D[i], 1e4 * U, max_abs(D, 16));
    }
    {
        double bad[4] = { NAN, 0.0, 0.0, 0.0 };
        CHECK(sd_expm(2, bad, E) != 0);
    }
}

/* Companion form of prod (z - p_k) (p given by re/im): x' = A x + b u, b = e_n. */
static void companion(int n, const double *re, const double *im, double *A, double *coef)
{
    /* polynomial with real coefficients from the (conjugate-paired) roots */
    double c[SD_MAX + 1] = { 1.0 };
    int i, j, k;
    for (k = 1; k <= n; ++k)
        c[k] = 0.0;
    for (k = 0; k < n; ++k) {
        if (im[k] != 0.0) {   /* (z^2 - 2 re z + re^2 + im^2), the pair at k, k + 1 */
            const double q1 = -2.0 * re[k], q0 = re[k] * re[k] + im[k] * im[k];
            const int deg = k;   /* roots so far */
            for (j = deg + 2; j >= 1; --j)
                c[j] += q1 * c[j - 1] + (j >= 2 ? q0 * c[j - 2] : 0.0);
            ++k;
        } else {
            for (j = k + 1; j >= 1; --j)
                c[j] -= re[k] * c[j - 1];
        }
    }
    for (i = 0; i < n * n; ++i)
        A[i] = 0.0;
    for (i = 0; i < n - 1; ++i)
        A[i * n + i + 1] = 1.0;
    for (j = 0; j < n; ++j)
        A[(n - 1) * n + j] = -c[n - j];
    for (k = 0; k <= n; ++k)
        coef[k] = c[k];
}

/* cond_inf of the real eigenvector matrix of a companion matrix with these roots: columns
 * Re and Im of [1, p, p^2, ...] (a Vandermonde matrix), by an explicit inverse. */
static double vandermonde_condition(int n, const double *re, const double *im)
{
    double V[SD_MAX * SD_MAX], W[SD_MAX * SD_MAX], I[SD_MAX * SD_MAX];
    int i, k;
    for (k = 0; k < n; ++k) {   /* p^i = pr + j pi; a pair's second column takes Im */
        double pr = 1.0, pi = 0.0;
        for (i = 0; i < n; ++i) {
            const double t = pr * re[k] - pi * im[k];
            V[i * n + k] = im[k] < 0.0 ? pi : pr;
            pi = pr * im[k] + pi * re[k];
            pr = t;
        }
    }
    for (i = 0; i < n * n; ++i) {
        W[i] = V[i];
        I[i] = i % (n + 1) == 0 ? 1.0 : 0.0;
    }
    if (sd_solve(n, W, I, n) != 0)
        return HUGE_VAL;
    return sd_norm_inf(n, n, V) * sd_norm_inf(n, n, I);
}

static void test_place(void)
{
    /* open loop: 1, 1 (the integrator and the rigid body), 0.98 +- 0.05j, 0.9; desired:
     * 0.91 +- 0.08j, 0.95 +- 0.05j, 0.985 (the servo's shape) */
    const double ore[5] = { 0.98, 0.98, 1.0, 1.0, 0.9 }, oim[5] = { 0.05, -0.05, 0, 0, 0 };
    const double dre[5] = { 0.91, 0.91, 0.95, 0.95, 0.985 };
    const double dim[5] = { 0.08, -0.08, 0.05, -0.05, 0 };
    double A[25], a[6], Ad[25], d[6], K[5], b[5] = { 0, 0, 0, 0, 1 };
    int i;
    companion(5, ore, oim, A, a);
    companion(5, dre, dim, Ad, d);
    CHECK(sd_place(5, A, b, dre, dim, K) == 0);
    /* A + b K is the companion of d: K_j = a_{n-j} - d_{n-j} (the last row's change). K = S V^-1
     * by LU, V the closed loop's eigenvectors, rounds by up to n^2 cond(V) u |K| (the LU's
     * growth bound): a Vandermonde matrix of poles this close together has cond about 1e7 */
    for (i = 0; i < 5; ++i)
        CHECK_CLOSE(K[i], a[5 - i] - d[5 - i], 25.0 * vandermonde_condition(5, dre, dim) * U,
                    max_abs(K, 5));
    /* a desired pole on an open-loop eigenvalue (0.9): the limit, K v = 0 for that mode */
    {
        const double re2[5] = { 0.91, 0.91, 0.95, 0.95, 0.9 };
        CHECK(sd_place(5, A, b, re2, dim, K) == 0);
        companion(5, re2, dim, Ad, d);
        for (i = 0; i < 5; ++i)
            CHECK_CLOSE(K[i], a[5 - i] - d[5 - i], 25.0 * vandermonde_condition(5, re2, dim) * U,
                        max_abs(K, 5));
    }
    /* a repeated pole cannot be placed by the eigenvectors: refused */
    {
        const double re3[5] = { 0.91, 0.91, 0.95, 0.95, 0.95 }, im3[5] = { 0.08, -0.08, 0, 0, 0 };
        CHECK(sd_place(5, A, b, re3, im3, K) != 0);
    }
    /* an unpaired complex pole is refused */
    {
        const double im4[5] = { 0.08, 0.08, 0.05, -0.05, 0 };
        CHECK(sd_place(5, A, b, dre, im4, K) != 0);
    }
}

static void test_dare(void)
{
    /* scalar: b^2 P^2 + (r (1 - a^2) - q b^2) P - q r = 0, the positive root */
    const double cases[][4] = { { 0.9, 0.5, 2.0, 0.3 }, { 2.0, 1.0, 1.0, 1.0 },
                                { 1.0, 1e-3, 1e4, 1e-2 } };
    size_t c;
    for (c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        const double a = cases[c][0], b = cases[c][1], q = cases[c][2], r = cases[c][3];
        const double B = r * (1.0 - a * a) - q * b * b;
        /* the positive root (-B + sqrt(B^2 + 4 b^2 q r)) / (2 b^2), rationalised */
        const double want = 2.0 * q * r / (B + sqrt(B * B + 4.0 * b * b * q * r));
        double P;
        CHECK(sd_dare(1, &a, &b, &q, r, &P) > 0);
        CHECK_CLOSE(P, want, 64.0 * U, want);
    }
    /* 3 states: the residual of the equation, relative to its terms */
    {
        const double b[3] = { 1e-4, 0.3, 0.0 }, Q[9] = { 10, 0, 0, 0, 0, 0, 0, 0, 1 };
        double P[9], T[9], APA[9], At[9], Pb[3], s = 0.0, bPb = 0.0, term = 0.0;
        int i, j;
        const double A2[9] = { 1.0, 5e-4, 0.0, -2.0, 0.99, 0.0, 0.0, 0.0, 0.5 };
        CHECK(sd_dare(3, A2, b, Q, 0.5, P) > 0);   /* the third mode: stable, unreachable */
        for (i = 0; i < 3; ++i)
            for (j = 0; j < 3; ++j)
                At[i * 3 + j] = A2[j * 3 + i];
        sd_mul(3, 3, 3, P, A2, T);
        sd_mul(3, 3, 3, At, T, APA);
        sd_mul(3, 3, 1, P, b, Pb);
        for (i = 0; i < 3; ++i)
            bPb += b[i] * Pb[i];
        {
            double APb[3];
            sd_mul(3, 3, 1, At, Pb, APb);
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) {
                    const double res = APA[i * 3 + j] - APb[i] * APb[j] / (0.5 + bPb)
                                       + Q[i * 3 + j] - P[i * 3 + j];
                    s = fabs(res) > s ? fabs(res) : s;
                    term = fabs(APA[i * 3 + j]) > term ? fabs(APA[i * 3 + j]) : term;
                }
        }
        CHECK(s <= 64.0 * 3.0 * U * term);
        /* an unstable mode the input cannot reach, weighted: no stabilising solution */
        {
            const double A3[9] = { 1.0, 5e-4, 0.0, -2.0, 0.99, 0.0, 0.0, 0.0, 1.01 };
            const double Q3[9] = { 10, 0, 0, 0, 0, 0, 0, 0, 1 };
            CHECK(sd_dare(3, A3, b, Q3, 0.5, P) == 0);
        }
    }
}

static void test_powers(void)
{
    sd_bounds bd;
    const double stable[4] = { 0.9, 0.0, 0.0, -0.5 }, unstable[4] = { 1.01, 0.0, 0.0, 0.5 };
    const double rot[4] = { 0.6, 0.8, -0.8, 0.6 }, jordan[4] = { 0.5, 100.0, 0.0, 0.5 };
    double P[4], Q[4] = { 1, 0, 0, 1 }, T[4];
    int k;
    sd_powers(2, stable, &bd);
    /* sum_k ||A^k|| = 1/(1 - 0.9) = 10, max 1; the bounds are at least these */
    CHECK(bd.stable && bd.sum >= 10.0 && bd.sup >= 1.0 && bd.sum <= 10.0 * 4.0);
    CHECK(bd.rho >= 0.9 * (1.0 - 1e-12) && bd.rho <= 1.0);
    sd_powers(2, unstable, &bd);
    CHECK(!bd.stable && bd.rho > 1.0);
    sd_powers(2, rot, &bd);                  /* |z| = 1: not asymptotically stable */
    CHECK(!bd.stable);
    sd_powers(2, jordan, &bd);
    /* ||A^k||_inf = 0.5^k + 100 k 0.5^(k-1): sum 2 + 400 = 402, max 100 (k = 1, 2) */
    CHECK(bd.stable && bd.sum >= 402.0 && bd.sup >= 100.5);
    sd_power(2, jordan, 1000, P);
    for (k = 0; k < 1000; ++k) {
        sd_mul(2, 2, 2, Q, jordan, T);
        Q[0] = T[0], Q[1] = T[1], Q[2] = T[2], Q[3] = T[3];
    }
    for (k = 0; k < 4; ++k)
        CHECK_CLOSE(P[k], Q[k], 1e-12, max_abs(Q, 4) + 1e-300);
}

int main(void)
{
    test_expm();
    test_place();
    test_dare();
    test_powers();
    return check_summary("test_fmu_servo_design");
}
