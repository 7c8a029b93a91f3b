/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Dense linear algebra for the ServoDrive model's design (servo_design.h): LU solves, the
 * matrix exponential, pole placement, the discrete Riccati equation and the powers of a closed
 * loop. Small fixed-capacity matrices on the stack; called only when the model is initialised.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "servo_design.h"

void sd_mul(int n, int k, int m, const double *A, const double *B, double *C)
{
    int i, j, l;
    for (i = 0; i < n; ++i)
        for (j = 0; j < m; ++j) {
            double s = 0.0;
            for (l = 0; l < k; ++l)
                s += A[i * k + l] * B[l * m + j];
            C[i * m + j] = s;
        }
}

double sd_norm_inf(int n, int m, const double *A)
{
    double best = 0.0;
    int i, j;
    for (i = 0; i < n; ++i) {
        double s = 0.0;
        for (j = 0; j < m; ++j)
            s += fabs(A[i * m + j]);
        if (!(s <= best))   /* NaN propagates */
            best = s;
    }
    return best;
}

/* LU with partial pivoting, B overwritten by A^-1 B. A pivot below `tiny` in magnitude is
 * replaced by tiny (inverse iteration's rule: the solution then points along the near-null
 * vector) when tiny > 0; with tiny = 0 a zero pivot fails. */
static int solve_core(int n, double *A, double *B, int m, double tiny)
{
    int i, j, k;
    for (k = 0; k < n; ++k) {
        int p = k;
        double piv;
        for (i = k + 1; i < n; ++i)
            if (fabs(A[i * n + k]) > fabs(A[p * n + k]))
                p = i;
        if (p != k) {
            for (j = 0; j < n; ++j) {
                double t = A[k * n + j];
                A[k * n + j] = A[p * n + j];
                A[p * n + j] = t;
            }
            for (j = 0; j < m; ++j) {
                double t = B[k * m + j];
                B[k * m + j] = B[p * m + j];
                B[p * m + j] = t;
            }
        }
        piv = A[k * n + k];
        if (!isfinite(piv))
            return 1;
        if (fabs(piv) < tiny || piv == 0.0) {
            if (!(tiny > 0.0))
                return 1;
            piv = A[k * n + k] = piv < 0.0 ? -tiny : tiny;
        }
        for (i = k + 1; i < n; ++i) {
            const double f = A[i * n + k] / piv;
            if (f == 0.0)
                continue;
            for (j = k + 1; j < n; ++j)
                A[i * n + j] -= f * A[k * n + j];
            for (j = 0; j < m; ++j)
                B[i * m + j] -= f * B[k * m + j];
        }
    }
    for (k = n - 1; k >= 0; --k)
        for (j = 0; j < m; ++j) {
            double s = B[k * m + j];
            for (i = k + 1; i < n; ++i)
                s -= A[k * n + i] * B[i * m + j];
            B[k * m + j] = s / A[k * n + k];
            if (!isfinite(B[k * m + j]))
                return 1;
        }
    return 0;
}

int sd_solve(int n, double *A, double *B, int m)
{
    return solve_core(n, A, B, m, 0.0);
}

/* B = D^-1 M D with D = diag(d) of powers of 2 (exact), rows and columns of B of about equal
 * norm (Parlett and Reinsch's balancing, as LAPACK's dgebal without permutations): a companion
 * matrix's last row of 1e8 comes down to the size of its ones. */
static void balance(int n, double *B, double *d)
{
    int i, j, sweep, done = 0;
    for (i = 0; i < n; ++i)
        d[i] = 1.0;
    for (sweep = 0; sweep < 64 && !done; ++sweep) {
        done = 1;
        for (i = 0; i < n; ++i) {
            double c = 0.0, r = 0.0, f = 1.0, s;
            for (j = 0; j < n; ++j)
                if (j != i) {
                    c += fabs(B[j * n + i]);
                    r += fabs(B[i * n + j]);
                }
            if (c == 0.0 || r == 0.0)
                continue;
            s = c + r;
            while (c < r / 2.0) {
                f *= 2.0;
                c *= 4.0;
            }
            while (c > r * 2.0) {
                f /= 2.0;
                c /= 4.0;
            }
            if ((c + r) / f < 0.95 * s) {
                done = 0;
                d[i] *= f;
                for (j = 0; j < n; ++j) {
                    B[i * n + j] /= f;
                    B[j * n + i] *= f;
                }
            }
        }
    }
}

int sd_expm(int n, const double *M, double *E)
{
    double X[SD_MAX * SD_MAX], Xk[SD_MAX * SD_MAX], T[SD_MAX * SD_MAX];
    double N[SD_MAX * SD_MAX], D[SD_MAX * SD_MAX], d[SD_MAX];
    double norm, c = 1.0, scale;
    int s = 0, k, i, j, e;
    const int nn = n * n, q = 6;
    memcpy(X, M, sizeof(double) * (size_t)nn);
    if (!isfinite(sd_norm_inf(n, n, X)))
        return 1;
    balance(n, X, d);
    norm = sd_norm_inf(n, n, X);
    if (!(norm <= 1e6))
        return 1;
    if (norm > 0.5) {
        (void)frexp(norm / 0.5, &e);   /* norm / 0.5 < 2^e */
        s = e;
    }
    scale = ldexp(1.0, -s);
    for (i = 0; i < nn; ++i) {
        X[i] *= scale;
        Xk[i] = X[i];
        N[i] = D[i] = 0.0;
    }
    for (i = 0; i < n; ++i)
        N[i * n + i] = D[i * n + i] = 1.0;
    /* N = sum c_k X^k, D = sum (-1)^k c_k X^k, c_k = c_k-1 (q - k + 1) / (k (2q - k + 1)) */
    for (k = 1; k <= q; ++k) {
        c *= (double)(q - k + 1) / (double)(k * (2 * q - k + 1));
        if (k > 1) {
            sd_mul(n, n, n, Xk, X, T);
            memcpy(Xk, T, sizeof(double) * (size_t)nn);
        }
        for (i = 0; i < nn; ++i) {
            N[i] += c * Xk[i];
            D[i] += (k % 2 ? -c : c) * Xk[i];
        }
    }
    if (sd_solve(n, D, N, n) != 0)
        return 1;
    for (k = 0; k < s; ++k) {
        sd_mul(n, n, n, N, N, T);
        memcpy(N, T, sizeof(double) * (size_t)nn);
    }
    /* e^M = D e^B D^-1 */
    for (i = 0; i < n; ++i)
        for (j = 0; j < n; ++j)
            E[i * n + j] = N[i * n + j] * d[i] / d[j];
    return 0;
}

int sd_place(int n, const double *A, const double *b, const double *re, const double *im,
             double *K)
{
    double V[SD_MAX * SD_MAX], S[SD_MAX], M[4 * SD_MAX * SD_MAX], x[2 * SD_MAX];
    const double tiny = DBL_EPSILON * (sd_norm_inf(n, n, A) + 1.0);
    int i, j, k;
    if (n < 1 || 2 * n > SD_MAX)
        return 1;
    for (i = 0; i < n;) {
        const int pair = im[i] != 0.0, m = pair ? 2 * n : n;
        double nrm = 0.0;
        if (pair && (i + 1 >= n || im[i + 1] != -im[i] || re[i + 1] != re[i]))
            return 1;
        for (j = 0; j < m * m; ++j)
            M[j] = 0.0;
        for (j = 0; j < n; ++j) {
            for (k = 0; k < n; ++k) {
                const double a = (j == k ? re[i] : 0.0) - A[j * n + k];
                M[j * m + k] = a;
                if (pair)
                    M[(n + j) * m + n + k] = a;
            }
            if (pair) {   /* [[re I - A, -im I], [im I, re I - A]] [x; y] = [b; 0] */
                M[j * m + n + j] = -im[i];
                M[(n + j) * m + j] = im[i];
            }
            x[j] = b[j];
            x[n + j] = 0.0;
        }
        if (solve_core(m, M, x, 1, tiny) != 0)
            return 1;
        for (j = 0; j < m; ++j)
            if (fabs(x[j]) > nrm)
                nrm = fabs(x[j]);
        if (!(nrm > 0.0) || !isfinite(nrm))
            return 1;
        for (j = 0; j < n; ++j) {
            V[j * n + i] = x[j] / nrm;
            if (pair)
                V[j * n + i + 1] = x[n + j] / nrm;
        }
        S[i] = 1.0 / nrm;
        if (pair)
            S[i + 1] = 0.0;
        i += pair ? 2 : 1;
    }
    /* K V = S, i.e. V' K' = S' */
    for (j = 0; j < n; ++j)
        for (k = 0; k < n; ++k)
            M[j * n + k] = V[k * n + j];
    if (sd_solve(n, M, S, 1) != 0)
        return 1;
    memcpy(K, S, sizeof(double) * (size_t)n);
    return 0;
}

static void symmetrize(int n, double *X)
{
    int i, j;
    for (i = 0; i < n; ++i)
        for (j = i + 1; j < n; ++j)
            X[i * n + j] = X[j * n + i] = 0.5 * (X[i * n + j] + X[j * n + i]);
}

int sd_dare(int n, const double *A, const double *b, const double *Q, double r, double *P)
{
    double Ak[SD_MAX * SD_MAX], G[SD_MAX * SD_MAX], H[SD_MAX * SD_MAX], W[SD_MAX * SD_MAX];
    double R[SD_MAX * 2 * SD_MAX], X1[SD_MAX * SD_MAX], X2[SD_MAX * SD_MAX];
    double T[SD_MAX * SD_MAX], U[SD_MAX * SD_MAX], At[SD_MAX * SD_MAX];
    const int nn = n * n;
    int i, j, it;
    if (n < 1 || n > SD_MAX || !(r > 0.0) || !isfinite(r))
        return 0;
    for (i = 0; i < n; ++i)
        for (j = 0; j < n; ++j) {
            Ak[i * n + j] = A[i * n + j];
            G[i * n + j] = b[i] * b[j] / r;
            H[i * n + j] = Q[i * n + j];
        }
    for (it = 1; it <= SD_DARE_ITERATIONS; ++it) {
        double delta = 0.0, size = 0.0;
        sd_mul(n, n, n, G, H, W);
        for (i = 0; i < n; ++i)
            W[i * n + i] += 1.0;
        for (i = 0; i < n; ++i)
            for (j = 0; j < n; ++j) {
                R[i * 2 * n + j] = Ak[i * n + j];
                R[i * 2 * n + n + j] = G[i * n + j];
            }
        if (sd_solve(n, W, R, 2 * n) != 0)
            return 0;
        for (i = 0; i < n; ++i)
            for (j = 0; j < n; ++j) {
                X1[i * n + j] = R[i * 2 * n + j];
                X2[i * n + j] = R[i * 2 * n + n + j];
                At[i * n + j] = Ak[j * n + i];
            }
        /* H += A' H X1 */
        sd_mul(n, n, n, H, X1, T);
        sd_mul(n, n, n, At, T, U);
        for (i = 0; i < nn; ++i) {
            delta += fabs(U[i]);
            H[i] += U[i];
            size += fabs(H[i]);
        }
        /* G += A X2 A' */
        sd_mul(n, n, n, X2, At, T);
        sd_mul(n, n, n, Ak, T, U);
        for (i = 0; i < nn; ++i)
            G[i] += U[i];
        /* A = A X1 */
        sd_mul(n, n, n, Ak, X1, T);
        memcpy(Ak, T, sizeof(double) * (size_t)nn);
        symmetrize(n, G);
        symmetrize(n, H);
        if (!isfinite(size) || !isfinite(sd_norm_inf(n, n, G)) || !isfinite(sd_norm_inf(n, n, Ak)))
            return 0;
        if (delta <= 1e-15 * size) {
            memcpy(P, H, sizeof(double) * (size_t)nn);
            return it;
        }
    }
    return 0;
}

void sd_powers(int n, const double *A, sd_bounds *out)
{
    double X[SD_MAX * SD_MAX], T[SD_MAX * SD_MAX];
    int i;
    out->stable = 0;
    out->sup = 1.0;
    out->sum = 1.0;
    out->rho = HUGE_VAL;
    memcpy(X, A, sizeof(double) * (size_t)(n * n));
    for (i = 0; i < 64; ++i) {
        const double p = sd_norm_inf(n, n, X);
        out->squarings = i;
        if (!isfinite(p) || p > 1e150) {
            out->rho = isfinite(p) ? exp(ldexp(log(p), -i)) : HUGE_VAL;
            return;
        }
        out->rho = p > 0.0 ? exp(ldexp(log(p), -i)) : 0.0;
        if (p <= 0.5) {
            /* the rest: sum_j>i P_j <= p^2 / (1 - p^2) <= 1/3 */
            out->sum *= (1.0 + p) * exp(1.0 / 3.0);
            out->stable = 1;
            return;
        }
        out->sup *= p > 1.0 ? p : 1.0;
        out->sum *= 1.0 + p;
        sd_mul(n, n, n, X, X, T);
        memcpy(X, T, sizeof(double) * (size_t)(n * n));
    }
}

void sd_power(int n, const double *A, uint64_t k, double *P)
{
    double B[SD_MAX * SD_MAX], T[SD_MAX * SD_MAX];
    const size_t bytes = sizeof(double) * (size_t)(n * n);
    int i;
    memcpy(B, A, bytes);
    for (i = 0; i < n * n; ++i)
        P[i] = 0.0;
    for (i = 0; i < n; ++i)
        P[i * n + i] = 1.0;
    while (k > 0u) {
        if (k & 1u) {
            sd_mul(n, n, n, P, B, T);
            memcpy(P, T, bytes);
        }
        k >>= 1;
        if (k > 0u) {
            sd_mul(n, n, n, B, B, T);
            memcpy(B, T, bytes);
        }
    }
}
