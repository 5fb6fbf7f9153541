#!/usr/bin/env bash
# Runs a libFuzzer target for a bounded time on its committed corpus (tests/fuzz/README.md):
#   bash tests/fuzz/run.sh build-fuzz/bin/fuzz_scene [SECONDS]
# The corpus of fuzz_scene is corpus/, that of fuzz_<name> corpus_<name>/ (fuzz_master_curve:
# corpus_master_curve/, fuzz_sweep: corpus_sweep/).
# New inputs go to a temporary directory (the committed corpus is only read); a crash leaves its
# input in build-fuzz/fuzz-artifacts/ and fails the run. The seed is fixed, so a run explores the
# same inputs in the same order on every machine (a slower machine sees a prefix of them).
set -euo pipefail
fuzzer="$1"
seconds="${2:-${RHABEL_FUZZ_SECONDS:-60}}"
here="$(cd "$(dirname "$0")" && pwd)"
artifacts="$(dirname "$(dirname "$fuzzer")")/fuzz-artifacts"
mkdir -p "$artifacts"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
# -max_len: scenes are small (the corpus's largest file is ~1 kB); 4 kB leaves room to grow.
# -timeout: one input (a parse and up to a few isolated solves at -O1 with ASan) takes
#  milliseconds to a second; 30 s means a hang. -rss_limit_mb: a leak or a runaway allocation.
name="$(basename "$fuzzer")"
corpus="$here/corpus"
[ "$name" = fuzz_scene ] || corpus="$here/corpus_${name#fuzz_}"
"$fuzzer" -seed=1 -max_total_time="$seconds" -max_len=4096 -timeout=30 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$artifacts/" "$work" "$corpus"
