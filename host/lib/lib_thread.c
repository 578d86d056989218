/*
 * lib_thread.c - liboffbench's pool of threads (lib_thread.h).
 */
#include "host/lib/lib_thread.h"

#include <pthread.h>
#include <stdlib.h>

typedef struct worker {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    void (*work)(void *), (*done)(void *);
    void *arg;              /* work: the task, NULL when there is none */
    struct worker *next;    /* in the idle list */
} worker;

static pthread_mutex_t pool_mu = PTHREAD_MUTEX_INITIALIZER;
static worker *idle;

/* A worker's life: wait for a task, run it, go idle, tell its end. */
static void *loop(void *p)
{
    worker *w = p;
    for (;;) {
        pthread_mutex_lock(&w->mu);
        while (!w->work)
            pthread_cond_wait(&w->cv, &w->mu);
        void (*work)(void *) = w->work, (*done)(void *) = w->done;
        void *arg = w->arg;
        pthread_mutex_unlock(&w->mu);
        work(arg);
        pthread_mutex_lock(&w->mu);
        w->work = NULL;  /* before it is idle: a next task set after this one stays */
        pthread_mutex_unlock(&w->mu);
        pthread_mutex_lock(&pool_mu);
        w->next = idle;
        idle = w;
        pthread_mutex_unlock(&pool_mu);
        done(arg);  /* the last use of arg */
    }
    return NULL;
}

/* In the child of a fork only the forking thread lives: the idle workers
 * are gone (their structs are left, unreachable), and the pool's lock may
 * have been held by one of them. */
static void forget_after_fork(void)
{
    pthread_mutex_init(&pool_mu, NULL);
    idle = NULL;
}

static pthread_once_t at_fork = PTHREAD_ONCE_INIT;

static void register_at_fork(void)
{
    pthread_atfork(NULL, NULL, forget_after_fork);
}

/* An idle worker, or a new one; NULL when none can be started. */
static worker *take(void)
{
    pthread_once(&at_fork, register_at_fork);
    pthread_mutex_lock(&pool_mu);
    worker *w = idle;
    if (w)
        idle = w->next;
    pthread_mutex_unlock(&pool_mu);
    if (w)
        return w;
    if (!(w = calloc(1, sizeof *w)))
        return NULL;
    pthread_t t;
    pthread_attr_t at;
    int ok = pthread_mutex_init(&w->mu, NULL) == 0;
    ok = ok && pthread_cond_init(&w->cv, NULL) == 0;
    ok = ok && pthread_attr_init(&at) == 0;
    ok = ok && pthread_attr_setdetachstate(&at, PTHREAD_CREATE_DETACHED) == 0 &&
         pthread_create(&t, &at, loop, w) == 0;
    if (!ok) {
        free(w);  /* (a mutex or cond that was made holds nothing to free on Linux) */
        return NULL;
    }
    pthread_attr_destroy(&at);
    return w;
}

int ob_lib_thread_run(void (*work)(void *), void (*done)(void *), void *arg)
{
    worker *w = take();
    if (!w)
        return -1;
    pthread_mutex_lock(&w->mu);
    w->work = work;
    w->done = done;
    w->arg = arg;
    pthread_cond_signal(&w->cv);
    pthread_mutex_unlock(&w->mu);
    return 0;
}
