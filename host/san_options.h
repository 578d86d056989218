/*
 * san_options.h - the AddressSanitizer defaults of the SAN=1 builds.
 *
 * Included once per program (host/main.c, tests/check.h); empty outside an
 * ASan build.
 *
 * Why: up to GCC 13 the sanitizer runtime's __tls_get_addr interceptor takes
 * a dynamic TLS block whose start lies 16 bytes past a page boundary for a
 * pre-2.25 glibc block and reads the two words before it as the block's
 * range (google/sanitizers#1322).  A block from glibc 2.36 lands there by
 * chance, and LeakSanitizer's tracer then dies on the garbage range at exit
 * ("Tracer caught signal 11", exit 1, no leak reported): about one run in
 * ten of the hostile-geometry job with PoCL's libraries loaded.  Not
 * intercepting __tls_get_addr only stops LeakSanitizer from scanning
 * dynamic TLS blocks for pointers (none of ours live there).  A user's own
 * ASAN_OPTIONS still apply on top of these defaults.
 */
#ifndef OB_SAN_OPTIONS_H
#define OB_SAN_OPTIONS_H

#if defined(__SANITIZE_ADDRESS__)
const char *__asan_default_options(void);
const char *__asan_default_options(void)
{
    return "intercept_tls_get_addr=0";
}
#endif

#endif
