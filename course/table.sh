#!/usr/bin/env bash
# docs/course.md's table (`course/table.sh > target/course-table.md`, then `cargo xtask figures`): every public course scene, rendered by the
# `render` example in f64, I16F16, I32F32 and f32 by the course rules, against the
# instructor's picture with compare.py (share of pixels beyond 2 levels); a scene without
# a picture: the other formats against our f64 render (marked "vs f64").
# Usage: course/table.sh (from the repository root; builds the example).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet --release --example render
out=target/course
mkdir -p "$out"
echo "| scene | entities | f64 % | I16F16 % | I32F32 % | f32 % |"
echo "|---|---|---|---|---|---|"
for scene in course/scenes/*.txt; do
    name=$(basename "$scene" .txt)
    ref=course/ref/$name.png
    # Entities: the words that open a block at the top level (brace depth 0).
    entities=$(tr -s '[:space:]' '\n' < "$scene" | awk '
        $0 == "{" { depth++; next }
        $0 == "}" { depth--; next }
        depth == 0 && want == "" { want = $0; next }
        depth == 0 && want != "" { count[want]++; want = "" }
        END { for (e in count) print e, count[e] }' | sort \
        | awk '{printf "%s%s×%s", sep, $1, $2; sep=", "}')
    row="| $name | $entities |"
    against=$ref
    if [ ! -e "$ref" ]; then
        # No picture: f64 is the reference of the other formats.
        against=$out/$name-f64.png
        target/release/examples/render "$scene" --format f64 --out "$against" >/dev/null 2>&1 || true
    fi
    for format in f64 i16f16 i32f32 f32; do
        png=$out/$name-$format.png
        if [ ! -e "$ref" ] && [ "$format" = f64 ]; then
            row="$row no picture |"
        elif err=$(target/release/examples/render "$scene" --format "$format" --out "$png" 2>&1 >/dev/null); then
            pct=$(python3 course/compare.py "$against" "$png" --tol 2 | sed -E 's/.*beyond_pct=([0-9.]+).*/\1/')
            if [ ! -e "$ref" ]; then pct="$pct vs f64"; fi
            row="$row $pct |"
        else
            row="$row not supported yet: \`${err##*: \`}\` |"
            row=$(echo "$row" | sed -E 's/ is not supported yet.*\|$/ |/')
        fi
    done
    echo "$row"
done
