# Sourced by regenerate-3d.sh and factor-prediction-3d.sh: writes one scene per level of
# scenes/hertz-sphere.json refined, and sets SCENES to their comma-separated paths.
#     sphere_levels SOURCE_DIR OUT_DIR "order:contact_size ..." WHO
sphere_levels() {
  SCENES=""
  for level in $3; do
    order=${level%%:*}
    size=${level#*:}
    file="$2/sphere-order$order-cs$size.json"
    /usr/bin/python3 - "$1/scenes/hertz-sphere.json" "$file" "$order" "$size" "$4" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["description"] = f"scenes/hertz-sphere.json with order {sys.argv[3]} and contact_size {sys.argv[4]} ({sys.argv[5]})"
scene["body"]["mesh"]["order"] = int(sys.argv[3])
scene["body"]["mesh"]["contact_size"] = float(sys.argv[4])
json.dump(scene, open(sys.argv[2], "w"), indent=2)
PY
    SCENES="$SCENES${SCENES:+,}$file"
  done
}
