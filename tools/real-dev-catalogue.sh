#!/bin/sh
# Prints a museum catalogue (docs/museum.md, "Catalogue") for the real-dev
# photographs: each file's title and source from DIR/MANIFEST.tsv. No sizes:
# the manifest records none, so every label says "Height not recorded".
#   tools/real-dev-catalogue.sh ../shared/data/real-dev > catalogue.csv
set -eu
dir=$(cd "${1:?usage: $0 REAL_DEV_DIR}" && pwd)
awk -F'\t' -v dir="$dir" '
NR == 1 { print "file,title,description"; next }
{
    title = $2; sub(/^[^'\'']*'\''/, "", title); sub(/'\'';.*$/, "", title); gsub(/"/, "\"\"", title)
    source = $2; sub(/, '\''.*$/, "", source); gsub(/"/, "\"\"", source)
    printf "%s/%s,\"%s\",\"%s.\"\n", dir, $1, title, source
}' "$dir/MANIFEST.tsv"
