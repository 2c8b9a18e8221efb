#!/usr/bin/env bash
# The README's "Course scene files" table: every public course scene whose entities fixray
# draws, rendered by the `render` example in f64, I16F16, I32F32 and f32 by the course
# rules, against the instructor's picture with compare.py (share of pixels beyond 2
# levels). Usage: course/table.sh (from the repository root; builds the example).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet --release --example render
out=target/course
mkdir -p "$out"
echo "| scene | entities | f64 % | I16F16 % | I32F32 % | f32 % |"
echo "|---|---|---|---|---|---|"
for ref in course/ref/*.png; do
    name=$(basename "$ref" .png)
    scene=course/scenes/$name.txt
    # Entities: the words that open a block at the top level (brace depth 0).
    entities=$(tr -s '[:space:]' '\n' < "$scene" | awk '
        $0 == "{" { depth++; next }
        $0 == "}" { depth--; next }
        depth == 0 && want == "" { want = $0; next }
        depth == 0 && want != "" { count[want]++; want = "" }
        END { for (e in count) print e, count[e] }' | sort \
        | awk '{printf "%s%s×%s", sep, $1, $2; sep=", "}')
    row="| $name | $entities |"
    for format in f64 i16f16 i32f32 f32; do
        png=$out/$name-$format.png
        if err=$(target/release/examples/render "$scene" --format "$format" --out "$png" 2>&1 >/dev/null); then
            pct=$(python3 course/compare.py "$ref" "$png" --tol 2 | sed -E 's/.*beyond_pct=([0-9.]+).*/\1/')
            row="$row $pct |"
        else
            row="$row not supported yet: \`${err##*: \`}\` |"
            row=$(echo "$row" | sed -E 's/ is not supported yet.*\|$/ |/')
        fi
    done
    echo "$row"
done
