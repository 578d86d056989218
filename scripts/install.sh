#!/bin/sh
# install.sh install|uninstall - what `make install` and `make uninstall` run
# (Makefile), from the repository root.  Every path comes from the
# environment the Makefile exports (OB_DESTDIR, OB_BINDIR, ..., OB_MANIFEST:
# make's DESTDIR, BINDIR, ... as given) and is only ever used quoted, so a
# PREFIX with spaces, glob characters or quotes names exactly itself.
#
# install writes the files and, as it writes each, appends its path (as
# PREFIX holds it, without DESTDIR) to the manifest OB_MANIFEST
# (PREFIX/share/offbench/install-manifest.txt); the paths of an earlier
# install's manifest are kept (an older library version is still ours).
# uninstall removes exactly the files (or links) the manifest lists, then
# the manifest; directories are left.  Without a manifest it says so and
# removes nothing.  A manifest line with a . or .. component is refused.
set -u
me=install.sh
nl='
'
D=${OB_DESTDIR-}
man=${OB_MANIFEST:?$me: OB_MANIFEST not set (run through make install / make uninstall)}

case $D$man in *"$nl"*) echo "$me: DESTDIR or PREFIX holds a newline: refused" >&2; exit 1 ;; esac

# record PATH: PATH (without DESTDIR) is ours, in the manifest
record() {
    printf '%s\n' "$1" >>"$D$man" || { echo "$me: cannot write the manifest $D$man" >&2; exit 1; }
}

# put MODE SRC PATH: install SRC as DESTDIR/PATH and record it
put() {
    case $3 in *"$nl"*) echo "$me: a path holds a newline: refused" >&2; exit 1 ;; esac
    printf 'install -m %s %s %s\n' "$1" "$2" "$D$3"
    install -m "$1" -- "$2" "$D$3" || exit 1
    record "$3"
}

# link TARGET PATH: DESTDIR/PATH a symbolic link to TARGET, recorded
link() {
    printf 'ln -sf %s %s\n' "$1" "$D$2"
    ln -sf -- "$1" "$D$2" || exit 1
    record "$2"
}

case ${1:-} in
    install)
        : "${OB_BINDIR:?}" "${OB_MAN1DIR:?}" "${OB_BASHCOMPDIR:?}" "${OB_ZSHCOMPDIR:?}" "${OB_LIBDIR:?}"
        : "${OB_INCLUDEDIR:?}" "${OB_LIBEXECDIR:?}" "${OB_BIN:?}" "${OB_MAN:?}" "${OB_SO:?}" "${OB_SONAME:?}" "${OB_SISL_SERVER:?}"
        install -d -- "$D$OB_BINDIR" "$D$OB_MAN1DIR" "$D$OB_BASHCOMPDIR" "$D$OB_ZSHCOMPDIR" "$D$OB_LIBDIR" \
            "$D$OB_INCLUDEDIR" "$D$OB_LIBEXECDIR" "$D$(dirname -- "$man")" || exit 1
        so=$(basename -- "$OB_SO")
        put 755 "$OB_BIN" "$OB_BINDIR/offbench"
        put 644 "$OB_MAN" "$OB_MAN1DIR/offbench.1"
        put 644 scripts/completion/offbench.bash "$OB_BASHCOMPDIR/offbench"
        put 644 scripts/completion/_offbench "$OB_ZSHCOMPDIR/_offbench"
        put 755 "$OB_SO" "$OB_LIBDIR/$so"
        link "$so" "$OB_LIBDIR/$OB_SONAME"
        link "$OB_SONAME" "$OB_LIBDIR/liboffbench.so"
        put 644 include/offbench.h "$OB_INCLUDEDIR/offbench.h"
        put 755 "$OB_SISL_SERVER" "$OB_LIBEXECDIR/offbench-sisl-server"
        # each path once, the earlier install's too
        sort -u -- "$D$man" >"$D$man.tmp" && mv -f -- "$D$man.tmp" "$D$man" || exit 1
        echo "wrote the manifest $D$man (make uninstall removes the files it lists)"
        ;;
    uninstall)
        if [ ! -f "$D$man" ]; then
            echo "$me: no manifest $D$man (make install writes it): nothing removed" >&2
            exit 0
        fi
        status=0
        while IFS= read -r f || [ -n "$f" ]; do
            [ -n "$f" ] || continue
            case /$f/ in
                */../* | */./*)
                    echo "$me: $D$man: '$f' has a . or .. component: not removed" >&2
                    status=1
                    continue
                    ;;
            esac
            if [ -L "$D$f" ] || [ -f "$D$f" ]; then
                printf 'rm %s\n' "$D$f"
                rm -f -- "$D$f" || status=1
            fi
        done <"$D$man"
        if [ "$status" -eq 0 ]; then
            rm -f -- "$D$man" || status=1
        else
            echo "$me: the manifest $D$man is kept" >&2
        fi
        exit "$status"
        ;;
    *)
        echo "usage: sh scripts/install.sh install|uninstall (through make install / make uninstall)" >&2
        exit 2
        ;;
esac
