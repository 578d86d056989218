/*
 * kernsrc.c - see kernsrc.h.
 */
#include "host/backend/kernsrc.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host/run/shard.h"

struct ob_embedded_file {
    const char *name;
    const char *text;
};
extern const struct ob_embedded_file ob_embedded_kernels[];

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n >= 0 && n < (1L << 24) && fseek(f, 0, SEEK_SET) == 0 && (buf = malloc((size_t)n + 1))) {
            if (fread(buf, 1, (size_t)n, f) != (size_t)n) {
                free(buf);
                buf = NULL;
            } else {
                buf[n] = '\0';
            }
        }
    }
    fclose(f);
    return buf;
}

static char *join(const char *core, const char *body)
{
    char *src = core && body ? malloc(strlen(core) + strlen(body) + 2) : NULL;
    if (src)
        sprintf(src, "%s\n%s", core, body);
    return src;
}

static char *embedded_source(void)
{
    const char *core = NULL, *body = NULL;
    for (int i = 0; ob_embedded_kernels[i].name; i++) {
        const char *nm = ob_embedded_kernels[i].name;
        if (strstr(nm, "metric_core.h"))
            core = ob_embedded_kernels[i].text;
        else if (strstr(nm, "measure.cl"))
            body = ob_embedded_kernels[i].text;
    }
    return join(core, body);
}

char *ob_kernel_source(char *where, size_t wlen)
{
    const char *dir = getenv("OFFBENCH_KERNELS");
    if (!dir || !*dir) {
        snprintf(where, wlen, "embedded copy of kernels/");
        return embedded_source();
    }
    /* a long path is cut: it only names the source in meta.json */
    snprintf(where, wlen, "%s", dir);
    const size_t n = strlen(dir) + 32;
    char *p1 = malloc(n), *p2 = malloc(n);
    char *core = NULL, *body = NULL, *src = NULL;
    if (p1 && p2) {
        snprintf(p1, n, "%s/metric_core.h", dir);
        snprintf(p2, n, "%s/measure.cl", dir);
        core = read_text(p1);
        body = read_text(p2);
        src = join(core, body);
    }
    free(p1);
    free(p2);
    free(core);
    free(body);
    return src;
}

uint64_t ob_kernel_hash(const char *src)
{
    return ob_fnv1a(OB_FNV_BASIS, src, strlen(src));
}

uint64_t ob_embedded_kernel_hash(void)
{
    static uint64_t h;  /* the text never changes: hashed once */
    if (!h) {
        char *src = embedded_source();
        h = src ? ob_kernel_hash(src) : 0;
        free(src);
    }
    return h;
}
