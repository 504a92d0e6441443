#!/usr/bin/env bash
# Copies the G-code corpus listed in tests/corpus/manifest.tsv into
# target/corpus/ (or $MOTION_HDL_CORPUS) and checks each file's git blob
# id. The programs are other projects' files under their own licences, so
# the repository keeps only the list.
#
#   bash tests/corpus/fetch.sh [--from DIR]
#
# With --from, a file is taken from a local copy of its repository in DIR:
# a clone DIR/<name> (for LinuxCNC/linuxcnc: DIR/linuxcnc), or a bare
# mirror DIR/<owner>+<name>/repo; the listed commit must be in it.
# Otherwise the file is downloaded from raw.githubusercontent.com. A file
# already present with the right blob id is kept.
set -euo pipefail
cd "$(dirname "$0")/../.."

from=""
if [ "${1:-}" = "--from" ]; then
  from=${2:?"--from needs a folder"}
elif [ $# -gt 0 ]; then
  echo "usage: bash tests/corpus/fetch.sh [--from DIR]" >&2
  exit 2
fi
dest=${MOTION_HDL_CORPUS:-target/corpus}
mkdir -p "$dest"

failed=0
while IFS=$'\t' read -r file repo commit path blob _licence _tools _outcome; do
  case "$file" in '#'* | '') continue ;; esac
  out="$dest/$file"
  if [ -f "$out" ] && [ "$(git hash-object "$out")" = "$blob" ]; then
    continue
  fi
  got=""
  if [ -n "$from" ]; then
    for git_dir in "$from/${repo#*/}/.git" "$from/${repo/\//+}/repo"; do
      if [ -d "$git_dir" ] && git --git-dir="$git_dir" cat-file -e "$commit:$path" 2>/dev/null; then
        git --git-dir="$git_dir" show "$commit:$path" >"$out"
        got=yes
        break
      fi
    done
  else
    curl -fsSL "https://raw.githubusercontent.com/$repo/$commit/$path" -o "$out" && got=yes
  fi
  if [ -z "$got" ]; then
    echo "not found: $file ($repo $commit:$path)" >&2
    rm -f "$out"
    failed=$((failed + 1))
  elif [ "$(git hash-object "$out")" != "$blob" ]; then
    echo "wrong contents: $file (blob $(git hash-object "$out"), the list says $blob)" >&2
    failed=$((failed + 1))
  fi
done <tests/corpus/manifest.tsv

if [ "$failed" -gt 0 ]; then
  echo "$failed corpus files missing or changed" >&2
  exit 1
fi
echo "corpus complete in $dest"
