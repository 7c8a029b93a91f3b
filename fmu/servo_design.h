/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The dense linear algebra the ServoDrive model designs its controllers with, once, when it is
 * initialised (servo_drive_model.c): small real matrices (at most SD_MAX x SD_MAX, row-major
 * double arrays), the matrix exponential for the exact zero-order hold, single-input pole
 * placement, the discrete algebraic Riccati equation, and the powers of a closed loop (its
 * stability and gain bounds). Double precision only, libm only, no allocation: the per-sample
 * loop of the model never calls these.
 */
#ifndef SERVO_DESIGN_H
#define SERVO_DESIGN_H

#include <stdint.h>

/** Largest matrix dimension: the closed loop of 4 plant and 9 controller states, with room. */
#define SD_MAX 16

/** C (n x m) = A (n x k) B (k x m); C must not alias A or B. */
void sd_mul(int n, int k, int m, const double *A, const double *B, double *C);

/**
 * @brief Solve A X = B by LU with partial pivoting: A (n x n) is overwritten by its factors, B
 * (n x m, m <= 2 SD_MAX) by X.
 * @return 0; 1 when a pivot is 0 or a value not finite (A singular to working precision).
 */
int sd_solve(int n, double *A, double *B, int m);

/**
 * @brief E = e^M (n x n) by scaling and squaring with the (6, 6) Pade approximant (Golub and
 * Van Loan, "Matrix Computations", 4th ed., algorithm 9.3.1), after an exact diagonal balancing
 * (powers of 2) B = D^-1 M D: B is scaled by 2^-s so that ||B 2^-s||_inf <= 1/2, where the
 * approximant's relative error is below 4e-21, squared s times, and E = D e^B D^-1.
 * @return 0; 1 when M is not finite or the balanced ||B||_inf exceeds 1e6.
 */
int sd_expm(int n, const double *M, double *E);

/**
 * @brief Single-input pole placement: K (1 x n) with eig(A + b K) = the poles (re[i] + j im[i]),
 * conjugate pairs adjacent with im > 0 first. For each pole the closed-loop eigenvector is
 * v = (p I - A)^-1 b scaled to unit length and K v = 1/|v| (a pair gives two real columns,
 * K Re v = 1/|v|, K Im v = 0), so K = S V^-1: its rounding is the condition number of the
 * closed loop's eigenvector matrix times the machine epsilon (Bauer-Fike's robustness measure).
 * A pole on an eigenvalue of A gets the limit (the eigenvector, K v = 0).
 * @return 0; 1 when V is singular (repeated poles, or a mode b cannot move).
 */
int sd_place(int n, const double *A, const double *b, const double *re, const double *im,
             double *K);

/**
 * @brief The stabilising solution P (n x n) of the discrete algebraic Riccati equation
 * P = A' P A - A' P b (r + b' P b)^-1 b' P A + Q (single input, r > 0, Q symmetric >= 0), by
 * the structure-preserving doubling algorithm (Chu, Fan, Lin and Wang, "Structure-preserving
 * algorithms for periodic discrete-time algebraic Riccati equations", Int. J. Control, 2004):
 * A_0 = A, G_0 = b b'/r, H_0 = Q; W = I + G_k H_k; A_k+1 = A_k W^-1 A_k,
 * G_k+1 = G_k + A_k W^-1 G_k A_k', H_k+1 = H_k + A_k' H_k W^-1 A_k; H_k -> P quadratically
 * (the error falls as rho^(2^k), rho the closed loop's spectral radius).
 * @return the iterations taken (1..SD_DARE_ITERATIONS); 0 when it did not converge or a value
 * is not finite (no stabilising solution, or one beyond double).
 */
int sd_dare(int n, const double *A, const double *b, const double *Q, double r, double *P);

/** Most doubling steps sd_dare() takes: 2^64 samples of the closed loop. */
#define SD_DARE_ITERATIONS 64

/** What the powers of a closed-loop matrix A say about it (sd_powers()). */
typedef struct sd_bounds {
    int stable;      /**< 1: ||A^(2^i)||_inf fell to 1/2 or below, so rho(A) < 1 */
    int squarings;   /**< i at which it did (or the last squaring tried) */
    double sup;      /**< bound on max_k ||A^k||_inf */
    double sum;      /**< bound on sum_k ||A^k||_inf */
    double rho;      /**< estimate of the spectral radius, ||A^(2^i)||^(2^-i) */
} sd_bounds;

/**
 * @brief Stability and gain bounds of x[k+1] = A x[k] + ... from the norms P_i = ||A^(2^i)||_inf
 * of repeated squares: ||A^k|| <= prod over k's binary digits of P_i, so
 * max_k ||A^k|| <= prod_i max(1, P_i) and sum_k ||A^k|| <= prod_i (1 + P_i); once P_i <= 1/2
 * (P_i+1 <= P_i^2) the rest of the product is at most e.
 */
void sd_powers(int n, const double *A, sd_bounds *out);

/** P = A^k by repeated squaring (n x n); about 2 log2(k) products. */
void sd_power(int n, const double *A, uint64_t k, double *P);

/** ||A||_inf of an n x m matrix: the largest row sum of |a_ij|. */
double sd_norm_inf(int n, int m, const double *A);

#endif
