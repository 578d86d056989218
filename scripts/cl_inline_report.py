#!/usr/bin/env python3
"""cl_inline_report.py [--kernels DIR] [--defines '-D A -D B' ...] [--ptx] -
what a GPU compiler that inlines everything (NVIDIA's does) gets from the
OpenCL program: per kernel, how many copies of each function full inlining
makes, the instructions that gives, and the private arrays in them.

The program is kernels/metric_core.h followed by kernels/measure.cl, as the
host builds it (host/backend/kernsrc.c), compiled by clang to LLVM IR for
nvptx64 (OpenCL C 1.2, no optimization, so every call site is still there).
For each kernel:
  copies(f)  the number of call paths from the kernel to f, with their
             multiplicity: what inlining every call makes of f
  inlined    sum over f of copies(f) x f's own IR instructions
  arrays     private arrays (allocas of array type) of f, times copies(f):
             their bytes if nothing shared them
With --ptx, also the CPU seconds LLVM's own NVPTX back end takes for the
program (opt -O2 with every function always inlined that the source does
not mark noinline, then llc) and the PTX lines it writes: a proxy for the driver's compiler, which does the same
and more (ptxas).  Each --defines gives one more variant of the program
(the host's per-metric, per-layout programs: -D OBC_ONLY_HAUSDORFF
-D OBC_ONLY_GROUPS and so on).

Needs clang, opt and llc (Debian: clang, llvm).  A development tool: not
run by the tests."""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile

CLANG = ["clang", "-x", "cl", "-cl-std=CL1.2", "-target", "nvptx64-nvidia-nvcl", "-Xclang",
         "-finclude-default-header", "-D__OPENCL_VERSION__=120"]


def ir_of(src, defines):
    """The LLVM IR text of src (OpenCL C) with the defines."""
    with tempfile.TemporaryDirectory() as d:
        p = os.path.join(d, "prog.cl")
        with open(p, "w", encoding="utf-8") as f:
            f.write(src)
        # unoptimized IR without -O0's blanket noinline: a noinline in it is the source's
        flags = ["-O1", "-Xclang", "-disable-llvm-passes"]
        r = subprocess.run(CLANG + defines + flags + ["-S", "-emit-llvm", p, "-o", "-"], capture_output=True,
                           text=True)
        if r.returncode != 0:
            sys.exit("cl_inline_report.py: clang failed:\n" + r.stderr[-2000:])
        return r.stdout


DEF = re.compile(r"^define .*?@([A-Za-z_][A-Za-z0-9_.]*)\(.*\)(?: [a-z_ ]+)? (#\d+)")
ATTR = re.compile(r"^attributes (#\d+) = \{(.*)\}")
CALL = re.compile(r"call [^@]*@([A-Za-z_][A-Za-z0-9_.]*)\(")
ARR = re.compile(r"= alloca (\[.*\]), align")


def arr_bytes(ty):
    """Bytes of an LLVM array type like [32 x [2 x double]]."""
    dims = [int(x) for x in re.findall(r"\[(\d+) x", ty)]
    base = ty.replace("[", "").replace("]", "").split(" x ")[-1].strip()
    size = {"double": 8, "i64": 8, "float": 4, "i32": 4, "i16": 2, "i8": 1}.get(base, 8)
    for n in dims:
        size *= n
    return size


def parse(ir):
    """Per defined function: its IR instructions, its calls (name -> count),
    its private arrays (list of bytes), whether it is a kernel."""
    funcs = {}
    cur = None
    for line in ir.splitlines():
        m = DEF.match(line)
        if m:
            cur = m.group(1)
            funcs[cur] = {"insns": 0, "calls": {}, "arrays": [], "kernel": "spir_kernel" in line
                          or "ptx_kernel" in line, "attr": m.group(2), "noinline": False}
            continue
        if cur is None:
            continue
        if line.startswith("}"):
            cur = None
            continue
        s = line.strip()
        if not s or s.endswith(":") or s.startswith(";"):
            continue
        funcs[cur]["insns"] += 1
        for c in CALL.findall(s):
            funcs[cur]["calls"][c] = funcs[cur]["calls"].get(c, 0) + 1
        a = ARR.search(s)
        if a:
            funcs[cur]["arrays"].append(arr_bytes(a.group(1)))
    # kernels: the metadata names them too
    for k in re.findall(r"!\{[^}]*@([A-Za-z_][A-Za-z0-9_]*), !\"kernel\"", ir):
        if k in funcs:
            funcs[k]["kernel"] = True
    noinl = {m.group(1) for m in map(ATTR.match, ir.splitlines()) if m and " noinline " in f" {m.group(2)} "}
    for f in funcs.values():
        f["noinline"] = f["attr"] in noinl and not f["kernel"]
    return funcs


def copies(funcs, root):
    """f -> number of call paths from root (root: 1)."""
    memo = {}

    def paths_into(f, stack):
        # copies(f) = sum over callers g of copies(g) x calls(g -> f)
        return None

    # topological order by DFS from root (the call graph has no recursion)
    order, seen = [], set()

    def dfs(f):
        if f in seen or f not in funcs:
            return
        seen.add(f)
        for c in funcs[f]["calls"]:
            if c in funcs and not funcs[c]["noinline"]:  # a call kept: compiled once, on its own
                dfs(c)
        order.append(f)

    dfs(root)
    order.reverse()  # callers before callees
    memo = {f: 0 for f in order}
    memo[root] = 1
    for f in order:
        for c, n in funcs[f]["calls"].items():
            if c in memo:
                memo[c] += memo[f] * n
    return memo


def kernel_names(funcs, ir):
    names = [f for f, v in funcs.items() if v["kernel"]]
    if not names:  # by the OBK_ARGS convention
        names = [f for f in funcs if f.startswith("ob_measure") or f.startswith("ob_fma")]
    return names


def cpu_children():
    """User and system CPU seconds of the finished child processes (a shared
    machine's load does not change them as it does the wall time)."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def ptx_cost(ir, funcs):
    """(seconds, PTX lines) of opt -O2 with every function inlined that the
    source does not keep out of line (noinline), then llc."""
    with tempfile.TemporaryDirectory() as d:
        ll = os.path.join(d, "p.ll")

        def mark(m):
            f = funcs.get(m.group(2))
            if not f or f["kernel"] or f["noinline"]:
                return m.group(0)
            return m.group(1) + " alwaysinline {"

        text = re.sub(r"^(define .*?@([A-Za-z_][A-Za-z0-9_.]*)\(.*) \{$", mark, ir, flags=re.M)
        with open(ll, "w", encoding="utf-8") as f:
            f.write(text)
        t0 = cpu_children()
        r = subprocess.run(["opt", "-O2", ll, "-S", "-o", os.path.join(d, "o.ll")], capture_output=True, text=True)
        if r.returncode != 0:
            return None, r.stderr[-500:]
        r = subprocess.run(["llc", "-march=nvptx64", "-mcpu=sm_80", os.path.join(d, "o.ll"), "-o",
                            os.path.join(d, "o.ptx")], capture_output=True, text=True)
        dt = cpu_children() - t0
        if r.returncode != 0:
            return None, r.stderr[-500:]
        with open(os.path.join(d, "o.ptx"), encoding="utf-8") as f:
            lines = sum(1 for _ in f)
        return dt, lines


def report(src, defines, ptx):
    ir = ir_of(src, defines)
    funcs = parse(ir)
    label = " ".join(defines) or "(no defines: every metric, both layouts)"
    print(f"== program {label}")
    total = 0
    roots, todo = [], list(kernel_names(funcs, ir))
    while todo:  # the kernels, then every out-of-line function they reach
        r = todo.pop(0)
        if r in roots:
            continue
        roots.append(r)
        for f in copies(funcs, r):
            todo += [c for c in funcs[f]["calls"] if c in funcs and funcs[c]["noinline"] and c not in roots]
    for k in roots:
        cp = copies(funcs, k)
        inl = sum(n * funcs[f]["insns"] for f, n in cp.items())
        arrays = sum(n * sum(funcs[f]["arrays"]) for f, n in cp.items())
        total += inl
        big = sorted(((n, f) for f, n in cp.items() if f != k), reverse=True)
        what = "kernel" if funcs[k]["kernel"] else "out of line"
        print(f"{what} {k}: {inl} IR instructions fully inlined ({len(cp) - 1} functions), "
              f"private arrays {arrays} bytes if none were shared")
        print("  copies: " + ", ".join(f"{f} {n}" for n, f in big[:12]))
        arr = [(n * sum(funcs[f]["arrays"]), f, funcs[f]["arrays"], n) for f, n in cp.items() if funcs[f]["arrays"]]
        arr.sort(reverse=True)
        print("  arrays: " + ", ".join(f"{f} {a} B x {n}" for _, f, a, n in arr[:6]))
    print(f"program: {total} IR instructions over its kernels and out-of-line functions")
    if ptx:
        dt, lines = ptx_cost(ir, funcs)
        if dt is None:
            print(f"ptx: failed: {lines}")
        else:
            print(f"ptx: opt -O2 (calls inlined but noinline ones) + llc nvptx64: {dt:.2f} s CPU, {lines} lines of PTX")
    return total


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kernels", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "kernels"))
    ap.add_argument("--defines", action="append", default=None,
                    help="one variant's defines, e.g. '-D OBC_ONLY_HAUSDORFF -D OBC_ONLY_GROUPS' (repeatable)")
    ap.add_argument("--ptx", action="store_true", help="time LLVM's NVPTX back end on each variant")
    a = ap.parse_args(argv)
    with open(os.path.join(a.kernels, "metric_core.h"), encoding="utf-8") as f:
        core = f.read()
    with open(os.path.join(a.kernels, "measure.cl"), encoding="utf-8") as f:
        body = f.read()
    src = core + "\n" + body
    for d in a.defines or [""]:
        report(src, d.split(), a.ptx)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
