#!/usr/bin/env bash
# The repository stands alone: no tracked file reads or cites anything outside it (the project's
# old working notes beside the checkout: the "shared" folder, its design notes and fixtures).
# Everything those held is in the repository: docs/design.md, docs/data/thesis-tables.json,
# tests/fixtures/philip/. Lists tracked files with git when there is a .git, else every file.
set -euo pipefail
S=$QUADAPT_SOURCE_DIR
cd "$S"
# The patterns are assembled so that this file does not match itself.
up='\.\.'/shared
design=DESIGN'\.md'
facts=LIBRARY'-'FACTS
fixt=philip'-'fixtures
envvar=QUADAPT'_'SHARED'_'DIR
pat="$up|$design|$facts|$fixt|$envvar"
if git -C "$S" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  files=$(git -C "$S" ls-files)
else
  files=$(find . -path ./build -prune -o -path './build*' -prune -o -type f -print | sed 's#^\./##')
fi
bad=$(printf '%s\n' "$files" | grep -v '^tests/fixtures/philip/.*\.msh$' |
      while IFS= read -r f; do [ -f "$f" ] && grep -I -l -E "$pat" -- "$f" || true; done)
if [ -n "$bad" ]; then
  echo "standalone: these files refer to files outside the repository:" >&2
  printf '%s\n' "$bad" | while IFS= read -r f; do grep -n -I -E "$pat" -- "$f" | sed "s#^#  $f:#" >&2; done
  exit 1
fi
# What replaced them is there.
for f in docs/design.md docs/data/thesis-tables.json tests/fixtures/philip/README.md \
         tests/fixtures/philip/input_ss15_fb_p2_3.msh tests/fixtures/philip/output_ss15_fb_p2_2.msh; do
  test -s "$f" || { echo "standalone: $f is missing" >&2; exit 1; }
done
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert len(d['cases'])==4" docs/data/thesis-tables.json
echo "standalone: ok ($(printf '%s\n' "$files" | wc -l) files checked)"
