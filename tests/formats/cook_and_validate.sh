#!/usr/bin/env bash
# Cooks one asset of every kind (distance single and layered, glossy, BC6H-compressed, with a
# sky, a level, a
# light field raw and BC1, a PEM) at toy sizes and validates every manifest written against
# its JSON Schema (docs/formats/*.schema.json) with Debian's python3-jsonschema.
#   cook_and_validate.sh SPECULA_COOK REPO_ROOT WORK_DIR
set -euo pipefail
cook=$1 root=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
assets=$root/assets
bake() { "$cook" bake "$@" >"$work/last.log" 2>&1 || { cat "$work/last.log"; exit 1; }; }
bake "$assets/sky_only/sky_only.gltf" --out "$work/single" --face-res 8 --plan analytic \
  --sky "$assets/scenes/env/pisa.jpg"
bake "$assets/room/room.gltf" --out "$work/layered" --face-res 8 --layers objects \
  --sky "$assets/scenes/env/field.jpg"
bake "$assets/room/room_rough_bands.gltf" --out "$work/glossy" --face-res 8 --plan analytic
bake "$assets/room/room_rough_bands.gltf" --out "$work/glossy_bc6h" --face-res 8 --plan analytic \
  --compress bc6h
bake "$assets/two_rooms/two_rooms.gltf" --out "$work/level" --face-res 8 --plan analytic
bake "$assets/room/room.gltf" --flavour lightfield --out "$work/lightfield" --cameras 2 --image-res 8
bake "$assets/room/room.gltf" --flavour lightfield --out "$work/lightfield_bc1" --cameras 2 \
  --image-res 8 --compress bc1
bake "$assets/room/room.gltf" --flavour pem --out "$work/pem" --samples 2 --face-res 8 \
  --image-size 64x48
bake "$assets/room/room.gltf" --flavour pem --out "$work/pem_bc6h" --samples 2 --face-res 8 \
  --image-size 64x48 --compress bc6h --mip-levels 4
mapfile -t manifests < <(find "$work" -name manifest.json -o -name level.json | sort)
# Every kind must be there: a bake that stopped writing one would otherwise pass unnoticed.
[ "${#manifests[@]}" -ge 11 ] || { echo "expected at least 11 manifests, found ${#manifests[@]}"; exit 1; }
/usr/bin/python3 "$root/tests/formats/validate_manifests.py" "$root/docs/formats" "${manifests[@]}"
