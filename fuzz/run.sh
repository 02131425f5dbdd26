#!/usr/bin/env bash
# Fuzzes the readers of user input with libFuzzer (Debian's clang), outside CI.
# Usage: fuzz/run.sh [seconds per target, default 300] [targets...]
# Targets: the mesh readers msh vtk vtu mesh tetgen (fuzz_read_mesh.cpp), the
# surface readers obj ply stl (fuzz_read_surface.cpp), the animation parsers
# json csv (fuzz_read_animation.cpp), the scene-file loader scene
# (fuzz_load_scene.cpp) and the skinned-character readers dae fbx gltf
# (fuzz_read_character.cpp: read_character, then prepare_character on a
# coarse lattice). Builds fuzz/build/fuzz_<target> with ASan and UBSan
# from the sources each needs (the scene loader and the character readers
# also link build/libsnh.a, assimp and OpenCL for what they do not fuzz), seeds fuzz/corpus/<target> from
# data/ and fuzz/seeds/, runs each fuzzer for the given time, one at a time
# and niced, and leaves crashing inputs in fuzz/artifacts/<target>/. Copy
# those to tests/fuzz_regressions/<target>/ with the format's extension once
# fixed (TetGen inputs are the .node text, a NUL byte, the .ele text: split
# them into a .node/.ele pair).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-300}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(msh vtk vtu mesh tetgen obj ply stl json csv scene dae fbx gltf)
CXX="${CXX:-clang++}"
mesh_sources=(host/io/mesh_readers.cpp host/io/gmsh_reader.cpp host/io/vtk_reader.cpp host/io/vtu_reader.cpp
              host/io/medit_reader.cpp host/io/tetgen_reader.cpp host/fem/mesh.cpp host/fem/rest_state.cpp)
surface_sources=("${mesh_sources[@]}" host/io/surface_io.cpp host/io/obj_reader.cpp host/io/ply_reader.cpp
                 host/io/stl_reader.cpp host/fem/closed_surface.cpp host/fem/surface_report.cpp
                 host/fem/fast_winding_number.cpp host/fem/voxelize.cpp)
# The scene loader and what it calls; the rest of the library (the solver,
# OpenCL) comes uninstrumented from the Release build's build/libsnh.a.
scene_sources=("${surface_sources[@]}" host/scene/scene_loader.cpp host/scene/scene_selectors.cpp
               host/scene/scene_schema.cpp host/rig/animation_reader.cpp host/rig/bone_transform.cpp host/rig/bones.cpp host/rig/winding_number.cpp
               host/fem/embedding.cpp host/fem/selection.cpp)
# The character readers (ufbx too; assimp is the system's, uninstrumented)
# and prepare_character's voxelizer, embedding, pieces and bones.
character_sources=("${surface_sources[@]}" host/character/character_reader.cpp host/character/collada_vertices.cpp
                   host/character/fbx_reader.cpp host/character/skin_weights.cpp host/character/character_bones.cpp
                   host/character/skinning.cpp host/third_party/ufbx/ufbx.c host/rig/bone_transform.cpp
                   host/rig/bones.cpp host/rig/winding_number.cpp host/fem/embedding.cpp host/fem/selection.cpp
                   host/fem/pieces.cpp)
flags=(-std=c++17 -g -O1 -fsanitize=address,undefined -fno-sanitize-recover=undefined -Iinclude -Ihost -Ikernels
       -isystem /usr/include/eigen3 -D_GNU_SOURCE -DCL_TARGET_OPENCL_VERSION=120 -DVIENNACL_WITH_OPENCL)
link_after=()
mkdir -p fuzz/build/obj
# Each library source compiled once (instrumented for coverage), again only
# when it changed; the targets link what they need.
objects() {
  local out=()
  for src in "$@"; do
    local o="fuzz/build/obj/${src//\//_}.o"
    if [ ! -f "$o" ] || [ "$src" -nt "$o" ] || [ -n "$(find include host -name '*.h' -newer "$o" -print -quit)" ]; then
      if [[ "$src" == *.c ]]; then  # ufbx: C99, its warnings upstream's
        nice -n 19 "${CC:-clang}" -std=c99 -g -O1 -fsanitize=address,undefined -fno-sanitize-recover=undefined -w \
          -fsanitize=fuzzer-no-link -c "$src" -o "$o"
      else
        nice -n 19 "$CXX" "${flags[@]}" -fsanitize=fuzzer-no-link -c "$src" -o "$o"
      fi
    fi
    out+=("$o")
  done
  echo "${out[@]}"
}
link() {  # link TARGET HARNESS DEFINE... -- SOURCES...
  local target="$1" harness="$2"
  shift 2
  local defines=()
  while [ "$1" != "--" ]; do defines+=("$1"); shift; done
  shift
  local objs
  objs=$(objects "$@")
  # shellcheck disable=SC2086
  nice -n 19 "$CXX" "${flags[@]}" -fsanitize=fuzzer "${defines[@]}" "$harness" $objs "${link_after[@]}" \
    -o "fuzz/build/fuzz_$target"
}
for f in "${targets[@]}"; do
  corpus="fuzz/corpus/$f"
  mkdir -p "$corpus" "fuzz/artifacts/$f"
  case "$f" in
    msh|vtk|vtu|mesh|tetgen) link "$f" fuzz/fuzz_read_mesh.cpp -DSNH_FUZZ_FORMAT="$f" -- "${mesh_sources[@]}" ;;
    obj|ply|stl)
      link "$f" fuzz/fuzz_read_surface.cpp -DSNH_FUZZ_FORMAT="$f" -DSNH_FUZZ_SURFACE_REPORT -- "${surface_sources[@]}" ;;
    json|csv) link "$f" fuzz/fuzz_read_animation.cpp -DSNH_FUZZ_FORMAT="$f" -- host/rig/animation_reader.cpp \
      host/rig/bone_transform.cpp ;;
    scene)
      [ -f build/libsnh.a ] || { echo "fuzz: build/libsnh.a is missing: build the library first" >&2; exit 1; }
      link_after=(build/libsnh.a -lOpenCL -lassimp)
      link scene fuzz/fuzz_load_scene.cpp -DSNH_DATA_DIR="\"$PWD/data\"" -- "${scene_sources[@]}"
      link_after=() ;;
    dae|fbx|gltf)
      [ -f build/libsnh.a ] || { echo "fuzz: build/libsnh.a is missing: build the library first" >&2; exit 1; }
      link_after=(build/libsnh.a -lOpenCL -lassimp)
      link "$f" fuzz/fuzz_read_character.cpp -DSNH_FUZZ_FORMAT="$f" -- "${character_sources[@]}"
      link_after=() ;;
    *) echo "fuzz: unknown target $f" >&2; exit 2 ;;
  esac
  case "$f" in
    msh|vtk|vtu|mesh|obj|ply|stl) cp data/meshes/*."$f" data/surfaces/*."$f" "$corpus/" 2>/dev/null || true ;;
    json) cp data/arm/*.json "$corpus/" ;;
    csv) cp fuzz/seeds/csv/*.csv "$corpus/" ;;
    scene) cp data/scenes/*.json "$corpus/" ;;
    dae|fbx|gltf) cp data/characters/*."$f" tests/data/character/*."$f" examples/character/*."$f" \
      fuzz/seeds/"$f"/* "$corpus/" 2>/dev/null || true ;;
    tetgen)
      for node in data/meshes/*.node; do
        { cat "$node"; printf '\0'; cat "${node%.node}.ele"; } > "$corpus/$(basename "${node%.node}").tetgen"
      done ;;
  esac
  # The characters' seeds are up to 84 KB (FBX); longer inputs are cut.
  max_len=65536
  case "$f" in dae|fbx|gltf) max_len=131072 ;; esac
  # assimp (the system's) leaks what it had built when it gives up on a
  # malformed file; LeakSanitizer still reports leaks from any other code.
  printf 'leak:libassimp.so\n' > fuzz/build/lsan.supp
  echo "fuzz: $f for ${seconds}s"
  LSAN_OPTIONS="suppressions=$PWD/fuzz/build/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}" \
  nice -n 19 "fuzz/build/fuzz_$f" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="$max_len" -artifact_prefix="fuzz/artifacts/$f/" -print_final_stats=1 2>&1 | grep -v " # Uses: " | tail -n 25 ||
    echo "fuzz: $f found a problem"
done
