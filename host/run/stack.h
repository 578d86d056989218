/*
 * stack.h - refuse, before any work, a thread stack too small for offbench.
 *
 * The fits and metrics keep their scratch (sample tables, normal equations,
 * Bezier pieces) in local arrays: measured over every method, metric and
 * split, a thread needs about 90 KiB of stack (the main thread about 110 KiB,
 * its environment included), and SISL and FLINT use stacks we do not see.
 * A thread whose stack is too small dies with SIGSEGV and no message, so
 * the program checks the settings that size its stacks instead: OMP_STACKSIZE
 * (or GOMP_STACKSIZE when it is unset) for the OpenMP workers, and the stack
 * limit (ulimit -s) for the main thread and for workers when neither is set.
 */
#ifndef OB_STACK_H
#define OB_STACK_H

/* The least stack a thread may have, in bytes: the ~110 KiB measured with
 * a margin for deeper paths and builds (-O1, sanitizers) that use more. */
#define OB_STACK_MIN_KIB 512ull
#define OB_STACK_MIN (OB_STACK_MIN_KIB * 1024ull)

/* Purpose: read a stack size as libgomp reads OMP_STACKSIZE.
 * Inputs:  s: blanks, digits (an optional '+'), blanks, an optional suffix
 *          B, K, M or G (either case; K when absent), blanks.
 * Outputs: *bytes: the size in bytes.
 * Returns: 0, or -1 when s is not such a size or it overflows 64 bits. */
int ob_stacksize_parse(const char *s, unsigned long long *bytes);

/* Purpose: check OMP_STACKSIZE (else GOMP_STACKSIZE) and the soft stack
 *          limit against OB_STACK_MIN.
 * Returns: 0; or -1 after ob_error() naming the variable (or the stack
 *          limit), its value and the minimum (the program exits 2). */
int ob_stack_check(void);

#endif
