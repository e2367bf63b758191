#!/usr/bin/env bash
# Builds the libFuzzer target (clang, with AddressSanitizer and UndefinedBehaviorSanitizer) and runs it.
# usage: bash scripts/fuzz.sh [SECONDS] [JOBS]     (default 600 s, 1 job); corpus in build/fuzz/corpus,
# seeded from config/*.yaml; any crash input is written to build/fuzz/ and the script exits non-zero.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
SECS="${1:-600}"
JOBS="${2:-1}"
OUT="$ROOT/build/fuzz"
bash "$ROOT/scripts/setup.sh" clang libclang-rt-14-dev  # libFuzzer and the sanitizers' runtime
mkdir -p "$OUT/corpus"
cp "$ROOT/config/finger.yaml" "$OUT/corpus/seed_finger.yaml"
printf 'chamber_count: 3\nchamber_gap_m: [0, 1e-5, 0.1]\nshear_modulus_pa: [1e-300, 1e12, 2e8]\n' >"$OUT/corpus/seed_lists.yaml"
# The model's sources as the library builds them: each batch kernel with its own instruction set (the model picks the
# widest the CPU has at run time), and no fused multiply-add anywhere (the kernels must round as the single evaluation).
CXXFLAGS=(-std=c++17 -O1 -g -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
  -fno-omit-frame-pointer -ffp-contract=off -Wno-psabi -Wno-unknown-warning-option -I"$ROOT/include"
  -isystem /usr/include/eigen3)
OBJECTS=()
for source in fuzz/fuzz_model src/core/parameters src/core/stages src/core/finger_model src/core/chamber_table \
  src/core/finger_inverse src/core/finger_batch src/core/simd_kernels src/core/yaml_parameters \
  src/core/tip_uncertainty src/core/batch_generic src/core/batch_avx2 src/core/batch_avx512; do
  case "$source" in
    *avx512) isa=(-mavx512f) ;;
    *avx2) isa=(-mavx2) ;;
    *) isa=() ;;
  esac
  object="$OUT/$(basename "$source").o"
  clang++ "${CXXFLAGS[@]}" "${isa[@]}" -c "$ROOT/$source.cpp" -o "$object"
  OBJECTS+=("$object")
done
clang++ -fsanitize=fuzzer,address,undefined "${OBJECTS[@]}" -lyaml-cpp -o "$OUT/fuzz_model"
cd "$OUT"
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ASAN_OPTIONS=detect_leaks=1 \
  ./fuzz_model -max_total_time="$SECS" -jobs="$JOBS" -workers="$JOBS" -max_len=4096 -timeout=10 \
  -artifact_prefix="$OUT/" corpus
