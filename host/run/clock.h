/*
 * clock.h - the two clocks the run's passes read: the calling thread's CPU
 * time (what a fit or a certificate cost, whatever else the machine did)
 * and the monotonic wall clock (a pass's length, the progress lines).
 */
#ifndef OB_CLOCK_H
#define OB_CLOCK_H

#include <time.h>

/* CPU time of the calling thread, ns (CLOCK_THREAD_CPUTIME_ID). */
static inline double ob_thread_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
}

/* The monotonic clock, seconds. */
static inline double ob_mono_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

#endif
