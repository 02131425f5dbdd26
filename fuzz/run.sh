#!/usr/bin/env bash
# Fuzzes each mesh reader with libFuzzer (Debian's clang), outside CI.
# Usage: fuzz/run.sh [seconds per format, default 300] [formats...]
# Builds fuzz/build/fuzz_<format> with ASan and UBSan from the reader
# sources (no OpenCL), seeds fuzz/corpus/<format> from data/meshes, runs each
# fuzzer for the given time and leaves crashing inputs in
# fuzz/artifacts/<format>/. Copy those to tests/fuzz_regressions/<format>/
# with the format's extension once fixed (TetGen inputs are the .node text,
# a NUL byte, the .ele text: split them into a .node/.ele pair).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-300}"
shift || true
formats=("$@")
[ ${#formats[@]} -eq 0 ] && formats=(msh vtk vtu mesh tetgen)
CXX="${CXX:-clang++}"
sources=(host/io/mesh_readers.cpp host/io/gmsh_reader.cpp host/io/vtk_reader.cpp host/io/vtu_reader.cpp
         host/io/medit_reader.cpp host/io/tetgen_reader.cpp host/fem/mesh.cpp host/fem/rest_state.cpp)
mkdir -p fuzz/build
for f in "${formats[@]}"; do
  "$CXX" -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -DSNH_FUZZ_FORMAT="$f" -Iinclude -Ihost fuzz/fuzz_read_mesh.cpp "${sources[@]}" -o "fuzz/build/fuzz_$f"
  corpus="fuzz/corpus/$f"
  mkdir -p "$corpus" "fuzz/artifacts/$f"
  case "$f" in
    msh) cp data/meshes/*.msh "$corpus/" ;;
    vtk) cp data/meshes/*.vtk "$corpus/" ;;
    vtu) cp data/meshes/*.vtu "$corpus/" ;;
    mesh) cp data/meshes/*.mesh "$corpus/" ;;
    tetgen)
      for node in data/meshes/*.node; do
        { cat "$node"; printf '\0'; cat "${node%.node}.ele"; } > "$corpus/$(basename "${node%.node}").tetgen"
      done ;;
  esac
  echo "fuzz: $f for ${seconds}s"
  "fuzz/build/fuzz_$f" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -artifact_prefix="fuzz/artifacts/$f/" -print_final_stats=1 2>&1 | tail -n 25 || echo "fuzz: $f found a problem"
done
