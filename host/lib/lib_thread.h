/*
 * lib_thread.h - liboffbench's own threads, for obx_run_batch: the driver
 * runs on one of them while the calling thread waits and calls the
 * progress callback, outside every lock the driver holds (include/offbench.h).
 */
#ifndef OB_LIB_THREAD_H
#define OB_LIB_THREAD_H

/* Purpose: run work(arg) on a library thread, then done(arg) there once
 *          the thread can take the next work (so a caller that waits for
 *          done and runs again gets the same thread back).  The threads
 *          are kept, idle, for reuse: the OpenMP threads each starts, and
 *          the sisl servers those start (methods/sisl.c, one per thread),
 *          serve the next batch instead of piling up; a thread is started
 *          only when none is idle (a batch inside a batch's callback).
 * Returns: 0; -1 when no thread can be started (work not run). */
int ob_lib_thread_run(void (*work)(void *), void (*done)(void *), void *arg);

#endif
