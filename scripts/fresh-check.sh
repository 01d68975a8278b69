#!/usr/bin/env bash
# Runs the README's two commands in a truly fresh Debian 12 root (debootstrap
# minbase + git, made by ../shared/tools/fresh-debian.sh), so that a package
# only a developer machine has cannot hide (issue 11, defect 13: `make`).
#
#   scripts/fresh-check.sh [ROOT]     default ROOT: /tmp/penumbra-fresh; needs root
#
# The root is made anew on every call. Each command runs in its own clean clone
# of this checkout's HEAD (uncommitted changes are not checked): first
# `bash scripts/main-job.sh`, then `bash .ci/run`, so the second also starts
# from a clean clone, as CI does (the packages the first installed stay). Prints
# the time of each and exits non-zero if either fails; logs in ROOT.logs/.
set -euo pipefail
cd "$(dirname "$0")/.."
tool=$(realpath "${FRESH_DEBIAN:-../shared/tools/fresh-debian.sh}")
root=${1:-/tmp/penumbra-fresh}
logs=$root.logs
[[ -z $(git status --porcelain --untracked-files=no) ]] ||
  echo "fresh-check: uncommitted changes are not part of the check (HEAD $(git rev-parse --short HEAD) is)"

"$tool" "$root" clean
rm -rf "$logs" && mkdir -p "$logs"
start=$SECONDS
"$tool" "$root"
echo "fresh-check: fresh Debian 12 root made in $((SECONDS - start)) s"

results=() status=0
for command in "bash scripts/main-job.sh" "bash .ci/run"; do
  log="$logs/$(echo "$command" | tr -c 'a-z0-9\n' '_').log"
  echo "fresh-check: running '$command' (log: $log)"
  start=$SECONDS rc=0
  "$tool" "$root" run "$command" >"$log" 2>&1 || rc=$?
  results+=("'$command': exit $rc in $((SECONDS - start)) s")
  if ((rc)); then
    status=1
    tail -n 30 "$log"
  fi
done
printf 'fresh-check: %s\n' "${results[@]}"
exit "$status"
