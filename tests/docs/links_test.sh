#!/usr/bin/env bash
# Every relative link of the README and docs/ (`[text](path)`, anchors and web addresses aside)
# names a file or folder that exists. Usage: links_test.sh SOURCE_DIR
set -euo pipefail
cd "$1"
broken=0
checked=0
while IFS= read -r doc; do
  dir=$(dirname "$doc")
  # The targets of [text](target), one per line, without a #anchor.
  while IFS= read -r target; do
    case $target in http://* | https://* | mailto:* | '#'* | '') continue ;; esac
    target=${target%%#*}
    checked=$((checked + 1))
    if [ ! -e "$dir/$target" ]; then
      echo "links_test: $doc links to $target, which does not exist" >&2
      broken=$((broken + 1))
    fi
  done < <(grep -o '\]([^)]*)' "$doc" | sed 's/^](//; s/)$//')
done < <(find README.md docs client/README.md docker/README.md -name '*.md' 2>/dev/null | sort)
[ "$checked" -gt 20 ] || { echo "links_test: only $checked links found" >&2; exit 1; }
[ "$broken" -eq 0 ] || exit 1
echo "links_test: $checked links, none broken"
