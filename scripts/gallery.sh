#!/usr/bin/env bash
# Renders every scene in scenes/ into OUT, composes a labelled contact sheet
# with OpenImageIO's oiiotool, and writes gallery.md from the stats, all in OUT;
# with --docs it also refreshes docs/showcase.png, docs/contact_sheet.png and
# docs/gallery.md (make gallery-docs), without machine paths in their metadata.
# Usage: scripts/gallery.sh PENUMBRA_BINARY OUT_DIR [--docs]
set -euo pipefail
bin=${1:?usage: gallery.sh PENUMBRA OUT}
out=${2:?usage: gallery.sh PENUMBRA OUT}
docs=${3:-}
root=$(cd "$(dirname "$0")/.." && pwd)
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
mkdir -p "$out"

tiles=()
for scene in "$root"/scenes/*.json; do
  name=$(basename "$scene" .json)
  echo "rendering $name" >&2
  "$bin" render "$scene" -o "$out/$name.png" --stats "$out/$name.json" --quiet
  secs=$(sed -n 's/.*"total": \([0-9.e+-]*\).*/\1/p' "$out/$name.json" | head -n 1)
  tile="$out/.tile-$name.png"
  oiiotool "$out/$name.png" --fit:pad=1 320x240 \
    --box:color=0,0,0,0.75:fill=1 0,0,320,28 \
    --text:x=8:y=20:size=15:color=1,1,0.6:font="$font" "$name  ($(printf '%.1f' "$secs") s)" \
    -o "$tile"
  tiles+=("$tile")
done

n=${#tiles[@]}
cols=4
rows=$(( (n + cols - 1) / cols ))
oiiotool "${tiles[@]}" --mosaic:pad=4 ${cols}x${rows} -o "$out/contact_sheet.png"
rm -f "${tiles[@]}"
echo "contact sheet: $out/contact_sheet.png" >&2

python3 "$root/scripts/gallery_md.py" "$out" > "$out/gallery.md"
echo "gallery: $out/gallery.md" >&2
[ "$docs" = "--docs" ] || exit 0

# Small copies for the docs (the README shows the showcase). The scene file's path
# and the command lines oiiotool recorded (with OUT's paths) are this machine's, so
# they stay out of committed images.
private=(--eraseattrib penumbra:scene_file --eraseattrib Software --eraseattrib Exif:ImageHistory)
oiiotool --nosoftwareattrib "$out/showcase.png" --resize 480x300 "${private[@]}" -o "$root/docs/showcase.png"
oiiotool --nosoftwareattrib "$out/contact_sheet.png" --resize 50% "${private[@]}" -o "$root/docs/contact_sheet.png"
cp "$out/gallery.md" "$root/docs/gallery.md"
echo "docs/showcase.png, docs/contact_sheet.png, docs/gallery.md updated" >&2
