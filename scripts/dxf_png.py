#!/usr/bin/python3
"""Draw a DXF file of `offbench run --export` back with ezdxf (Debian
python3-ezdxf) and matplotlib (python3-matplotlib) into a PNG: the file is
read and audited by ezdxf, and its SPLINE entities are drawn by ezdxf's own
drawing add-on, pieces in alternating colours so the joints show.

usage: scripts/dxf_png.py FILE.dxf OUT.png [TITLE]
Exit status 0; 2 when the file cannot be read or ezdxf / matplotlib are
missing (the message says which)."""
import sys


def main(argv):
    if len(argv) not in (3, 4):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from ezdxf import recover
        from ezdxf.addons.drawing import Frontend, RenderContext
        from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
        from ezdxf.addons.drawing.properties import LayoutProperties
    except ImportError as e:
        print(f"dxf_png.py: {e}: install python3-ezdxf and python3-matplotlib", file=sys.stderr)
        return 2
    try:
        doc, auditor = recover.readfile(argv[1])
    except (IOError, OSError) as e:
        print(f"dxf_png.py: {argv[1]}: {e}", file=sys.stderr)
        return 2
    if auditor.has_errors:
        print(f"dxf_png.py: {argv[1]}: ezdxf's audit found {len(auditor.errors)} errors", file=sys.stderr)
        return 2
    msp = doc.modelspace()
    splines = msp.query("SPLINE")
    for i, s in enumerate(splines):
        s.dxf.color = 1 if i % 2 == 0 else 5   # red, blue (AutoCAD colour index)
    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_axes([0.02, 0.02, 0.96, 0.90])
    ctx = RenderContext(doc)
    white = LayoutProperties.from_layout(msp)
    white.set_colors("#ffffff")
    Frontend(ctx, MatplotlibBackend(ax)).draw_layout(msp, finalize=True, layout_properties=white)
    title = argv[3] if len(argv) == 4 else argv[1]
    fig.suptitle(f"{title}\n{len(splines)} SPLINE entities, drawn by ezdxf {__import__('ezdxf').__version__}",
                 fontsize=9)
    fig.savefig(argv[2], dpi=100, facecolor="white")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
