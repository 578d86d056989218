#!/bin/sh
# history_from_site.sh SITE_DIR HISTORY_DIR - fills the nightly history
# store from a published report (docs/nightly.md "Nightly in CI").
#
# A site written by `scripts/report.py HISTORY --out SITE --copy-files`
# holds a copy of every run of the store in SITE/runs/NAME/ (run.json, the
# run sets' results.csv, samples.csv and meta.json, report.md, the logs):
# the store itself, as it was when the site was made.  A CI runner that
# starts empty, without the cache the recipes in scripts/ci/ keep the store
# in, can get it back from the last published site (the GitLab recipe
# downloads the pages job's artifact).  Each run of SITE/runs/ that is not in
# HISTORY_DIR already is copied there (a run already there is left as it
# is); only directories named like a run (UTC stamp first, as
# scripts/nightly_history.sh names them) and holding a run.json count, and
# symbolic links are copied as links, never followed.
# Exit status: 0 done (also when SITE_DIR has no runs: nothing to restore,
# said on stderr), 2 bad usage or a copy that failed.
set -u
[ $# -eq 2 ] || { echo "usage: history_from_site.sh SITE_DIR HISTORY_DIR" >&2; exit 2; }
site=$1 hist=$2
if [ ! -d "$site/runs" ]; then
    echo "history_from_site: $site/runs: no runs to restore (the history starts here)" >&2
    exit 0
fi
mkdir -p "$hist" || exit 2
n=0 kept=0
for r in "$site"/runs/*; do
    [ -d "$r" ] && [ ! -L "$r" ] && [ -f "$r/run.json" ] || continue
    name=${r##*/}
    case "$name" in
        [0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]T[0-9][0-9][0-9][0-9][0-9][0-9]Z_*) ;;
        *) continue ;;
    esac
    if [ -e "$hist/$name" ] || [ -L "$hist/$name" ]; then
        kept=$((kept + 1))
        continue
    fi
    # under a dot name, then renamed: the store never shows half a run
    tmp="$hist/.restore-$name"
    rm -rf -- "$tmp"
    cp -RP -- "$r" "$tmp" && mv -- "$tmp" "$hist/$name" \
        || { rm -rf -- "$tmp"; echo "history_from_site: copying $r into $hist failed" >&2; exit 2; }
    n=$((n + 1))
done
echo "history_from_site: $n runs restored into $hist from $site ($kept already there)" >&2
exit 0
