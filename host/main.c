/*
 * main.c - ./offbench: dispatch to the subcommands.
 */
#include <stdio.h>
#include <string.h>

#include "buildinfo.h"
#include "host/backend/clrt.h"
#include "host/cli/cliopts.h"
#include "host/cli/commands.h"
#include "host/cli/external_opt.h"
#include "host/cli/methods_file.h"
#include "host/cli/suggest.h"
#include "host/diag.h"
#include "host/run/mpirun.h"
#include "host/run/signals.h"
#include "host/run/stack.h"
#include "host/san_options.h"

/* The version is the date of the commit built (there are no numbered
 * releases); the commit and its dirty flag say exactly what was built. */
#define OB_VERSION OB_GIT_DATE

static const char usage[] =
    "usage:\n"
    "  ./offbench run    [--curves FILE] [--curve ID,...] [--random N[:SEED]] [--methods LIST|all]\n"
    "                    [--tols 1e-1,1e-2,...] [--metric bound|radial|normal|hausdorff]\n"
    "                    [--split mid|maxerr|greedy|optimal] [--backend auto|opencl|cpu] [--device NAME]\n"
    "                    [--threads N]\n"
    "                    [--samples S] [--max-depth N] [--max-segments N] [--inflections yes|no]\n"
    "                    [--param METHOD.NAME=VALUE]\n"
    "                    [--job-timeout S] [--reps N] [--shard K/N] [--out DIR | --resume DIR]\n"
    "                    [--export DIR]   (each job's approximation: JSON, .curves, DXF, SVG)\n"
    "  ./offbench merge  DIR... --out DIR   (the shards of one run into its results.csv)\n"
    "  ./offbench certify RUN_DIR [--methods LIST] [--tols LIST] [--curves ID,...] [--threads N]\n"
    "                    (a finished run certified after the fact: the columns of run --certify)\n"
    "  ./offbench compare BASE NEW [--format md|csv] [--out FILE] [--err-rtol R] [--time-threshold F]\n"
    "                    (files or run directories; exit 0 same, 1 regression, 2 error, 3 not comparable)\n"
    "  ./offbench summary RUN_DIR [--format md|csv|latex] [--out FILE] [--methods LIST] [--curves ID,...]\n"
    "                    [--family F] [--metric M] [--baseline RUN_DIR2 | --archive A]   (the paper table)\n"
    "  ./offbench draw   --curve ID --method M --tol T [--d D] [run options] --out FILE.svg\n"
    "  ./offbench draw   --approx FILE --curve ID --d D --out FILE.svg   (a file's pieces coloured by their error)\n"
    "  ./offbench trace  --curve ID --method M --tol T [--d D] [run options] [--out FILE.csv]\n"
    "  ./offbench measure --curve ID --d D --approx FILE [--approx FILE]... [--curves FILE] [--metric M|all]\n"
    "                    [--samples S] [--per-piece FILE.csv] [--draw FILE.svg]\n"
    "                    (the error of approximations in .curves, JSON, DXF or SVG files; where it is)\n"
    "  ./offbench atlas  [--out DIR]        (the Offset Atlas: exact offset degrees)\n"
    "  ./offbench tables [--out DIR] [--table SOURCE:TABLE,...] [--protocols LIST] [run options]\n"
    "  ./offbench list   methods|curves|columns|devices\n"
    "  ./offbench bench  [--out DIR] [--quick]\n"
    "  ./offbench worker METHOD   (a built-in method as an external worker: docs/external-methods.md)\n"
    "  ./offbench --version   (the build: version, git commit, flags, OpenCL loader)\n"
    "Every command takes --external NAME=COMMAND: a method in any language (docs/external-methods.md),\n"
    "and --methods-file FILE: such methods named in a file (methods/cad.methods: OpenCASCADE, lib2geom).\n"
    "Every command takes --help (its options, exit 0) and --name=value.  See README.md.\n";

static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage, stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "run") == 0)
        return ob_cmd_run(argc - 1, argv + 1, argc, argv);
    if (strcmp(cmd, "list") == 0)
        return ob_cmd_list(argc - 1, argv + 1);
    if (strcmp(cmd, "tables") == 0)
        return ob_cmd_tables(argc - 1, argv + 1, argc, argv);
    if (strcmp(cmd, "compare") == 0)
        return ob_cmd_compare(argc - 1, argv + 1);
    if (strcmp(cmd, "atlas") == 0)
        return ob_cmd_atlas(argc - 1, argv + 1);
    if (strcmp(cmd, "summary") == 0)
        return ob_cmd_summary(argc - 1, argv + 1);
    if (strcmp(cmd, "certify") == 0)
        return ob_cmd_certify(argc - 1, argv + 1);
    if (strcmp(cmd, "merge") == 0)
        return ob_cmd_merge(argc - 1, argv + 1);
    if (strcmp(cmd, "draw") == 0)
        return ob_cmd_draw(argc - 1, argv + 1);
    if (strcmp(cmd, "trace") == 0)
        return ob_cmd_trace(argc - 1, argv + 1);
    if (strcmp(cmd, "measure") == 0)
        return ob_cmd_measure(argc - 1, argv + 1);
    if (strcmp(cmd, "bench") == 0)
        return ob_cmd_bench(argc - 1, argv + 1);
    if (strcmp(cmd, "worker") == 0)
        return ob_cmd_worker(argc - 1, argv + 1);
    if (strcmp(cmd, "--version") == 0 || strcmp(cmd, "version") == 0) {
        const int prc = ob_cli_no_options("  (the build: version, git commit, flags, OpenCL loader)", argc - 1, argv + 1);
        if (prc != OB_CLI_OK)
            return prc == OB_CLI_HELP ? 0 : 2;
        char cl[512];
        ob_cl_loader_status(cl, sizeof cl);
        printf("offbench %s\ngit commit: %s\ngit dirty: %s\ncompiler: gcc %s\ncflags: %s\nOpenCL: %s\n", OB_VERSION,
               OB_GIT_COMMIT, OB_GIT_DIRTY ? "yes (uncommitted changes at build time)" : "no", __VERSION__, OB_CFLAGS,
               cl);
        return 0;
    }
    if (strcmp(cmd, "help") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0) {
        const int prc = ob_cli_no_options("  (every command)", argc - 1, argv + 1);
        if (prc != OB_CLI_OK)
            return prc == OB_CLI_HELP ? 0 : 2;
        fputs(usage, stdout);
        return 0;
    }
    char note[96];
    ob_error("unknown command '%s'%s", cmd, ob_suggest_command(usage, cmd, note, sizeof note));
    fputs(usage, stderr);
    return 2;
}

/* Under mpirun (a build with MPI) every rank runs the command; see mpirun.h.
 * The thread stacks are checked first (stack.h). */
int main(int argc, char **argv)
{
    /* every command may run fits on OpenMP threads: a stack too small for
     * them would crash one mid-run with SIGSEGV; refuse it before any work */
    if (ob_stack_check() != 0)
        return 2;
    /* one stop flag for every command: each long loop polls it, and a
     * stopped command ends with 128 + the signal (signals.h); installed
     * before MPI, OpenMP or OpenCL start a thread, so that every thread
     * leaves SIGINT/SIGTERM to the one watcher */
    ob_signals_install();
    if (ob_mpi_init(&argc, &argv) != 0) {
        ob_error("MPI could not start");
        return 1;
    }
    /* external methods first: every command then sees them as methods */
    if (ob_external_args(&argc, argv) != 0 || ob_methods_file_args(&argc, argv) != 0) {
        ob_mpi_finalize();
        return 2;
    }
    const int rc = ob_stop_status(dispatch(argc, argv));
    ob_mpi_finalize();
    return rc;
}
