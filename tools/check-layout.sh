#!/bin/sh
# Checks the two measurable rules of the source layout (docs/plugins.md,
# "Layout rules"), and prints the lines of each folder of src/:
#
#  1. no folder of src/ holds more than 20% of the source lines (every .c,
#     .h and .cpp under src/, blank lines and comments included);
#  2. a header is included across folders only if it is that folder's
#     interface: a file of src/A/ may include its own folder's headers, the
#     public API (include/celadon/*.h), and from another folder src/B/ only
#     B/B.h. The public headers include only public headers.
#
# Exit status 0 when both hold, 1 otherwise (each violation on one line).
# Run from the repository's top folder (make check-layout does).
set -eu

limit_percent=20
fail=0

[ -d src ] && [ -d include/celadon ] || {
    echo "check-layout: run from the repository's top folder" >&2
    exit 2
}

# --------------------------------------------------------------- line counts
counts=$(find src -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' \) -exec wc -l {} + |
    awk '$2 != "total" { split($2, p, "/"); n[p[2]] += $1; t += $1 }
         END { for (f in n) printf "%s %d %d\n", f, n[f], t }' | sort -k2,2nr)
total=$(echo "$counts" | awk 'NR == 1 { print $3 }')
echo "check-layout: source lines per folder of src/ (total $total, limit $limit_percent%):"
echo "$counts" | while read -r folder lines tot; do
    pct=$(awk -v l="$lines" -v t="$tot" 'BEGIN { printf "%.1f", 100 * l / t }')
    printf "  %-14s %6d  %5s%%\n" "$folder" "$lines" "$pct"
done
over=$(echo "$counts" | awk -v lim="$limit_percent" '100 * $2 > lim * $3 { print $1 }')
for folder in $over; do
    echo "check-layout: src/$folder/ holds more than $limit_percent% of the source lines" >&2
    fail=1
done

# ------------------------------------------------------------------ includes
# Every quoted #include of every source file, as "file included".
includes=$(grep -rHoE '^[[:space:]]*#[[:space:]]*include[[:space:]]+"[^"]+"' src include |
    sed -E 's/:[[:space:]]*#[[:space:]]*include[[:space:]]+"([^"]+)"/ \1/')
# judge: prints each include of "file included" lines that breaks rule 2.
judge() {
    awk '
        {
            file = $1; inc = $2
            n = split(file, p, "/")
            if (p[1] == "include") {                    # a public header
                if (inc !~ /^celadon\/[^\/]+\.h$/) print file ": includes \"" inc "\", which is not public"
                next
            }
            folder = p[2]
            if (inc ~ /^celadon\//) next                # the public API
            m = split(inc, q, "/")
            if (m == 1) next                            # a header beside the file
            if (q[1] == folder) next                    # its own folder
            if (m == 2 && q[2] == q[1] ".h") next       # another folder: its interface
            print file ": includes \"" inc "\", not the interface of src/" q[1] "/ (" q[1] "/" q[1] ".h)"
        }'
}
bad=$(echo "$includes" | judge)
if [ -n "$bad" ]; then
    echo "$bad" | sed 's/^/check-layout: /' >&2
    fail=1
fi

if [ "$fail" -eq 0 ]; then
    echo "check-layout: every folder within $limit_percent%; headers cross folders only as interfaces"
fi
exit "$fail"
