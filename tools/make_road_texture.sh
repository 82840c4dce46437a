#!/usr/bin/env bash
# Write data/road_texture.dat, the sample road texture of data/patch_texture.nml, from
# data/road_sample.dat: every 5th line of the profile (x from 0 to 4 m by 10 mm) plus a rocking
# across the road, h(x, y) = h_sample(x) + 0.5e-3*sin(2*pi*x/0.4)*sin(2*pi*y/0.2) [m], at the
# five lateral positions y = -0.1, -0.05, 0, 0.05, 0.1 m. Format: src/greenconv/model/road_texture.f90.
#
#   bash tools/make_road_texture.sh [OUTPUT]      (default data/road_texture.dat)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
output=${1:-data/road_texture.dat}
awk 'BEGIN {
  pi = atan2(0, -1)
  print "# greenconv sample road texture: heights [m] on an x-y grid, for data/patch_texture.nml."
  print "# Format (src/greenconv/model/road_texture.f90): the first data line holds the lateral"
  print "# positions y [m]; every later data line x [m] and the heights [m] at each y; bilinear in between."
  print "# Written by tools/make_road_texture.sh from data/road_sample.dat (every 5th line: x from 0 to 4 m"
  print "# by 10 mm) plus a rocking across the road: h(x, y) = h_sample(x) + 0.5e-3*sin(2*pi*x/0.4)*sin(2*pi*y/0.2)."
  printf "%9s", ""
  for (j = 0; j < 5; j++) printf " %15.4f", -0.1 + 0.05*j
  printf "\n"
}
!/^#/ && NF == 2 && (n++ % 5 == 0) && $1 <= 4.0 + 1e-9 {
  printf "%9.3f", $1
  for (j = 0; j < 5; j++) { y = -0.1 + 0.05*j; printf " %15.7E", $2 + 0.5e-3*sin(2*pi*$1/0.4)*sin(2*pi*y/0.2) }
  printf "\n"
}' data/road_sample.dat > "$output.part"
mv "$output.part" "$output"
echo "make_road_texture: wrote $output"
