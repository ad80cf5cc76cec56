"""Test layers.public_includes_only: the command and the Python module use the
library through its public headers alone, and the public headers include
no internal one.

A layer's include root src/<folder>/include/ holds its public headers in
minksum/ and its internal ones in <layer>/ (docs/architecture.md).  The
command (cli/, cli/play/) and the Python module (python/) are built against
libminksum.a, whose include path has every root, so the compiler cannot tell
them apart; this script does: an #include of "<layer>/..." or <<layer>/...>
for an internal folder <layer> (kernel/, mesh/, sum/, ...) in cli/ or
python/, or in a public header, is reported with its file and line.

Usage: check_includes.py SOURCE_DIR
"""

import glob
import os
import re
import sys


def main():
    root = sys.argv[1]
    internal = sorted({os.path.basename(d) for d in glob.glob(os.path.join(root, "src", "**", "include", "*"),
                                                                 recursive=True)
                       if os.path.isdir(d) and os.path.basename(d) != "minksum"})
    if not internal:
        sys.exit(f"{root}: no internal header folders found under src/*/include/")
    pattern = re.compile(r'^\s*#\s*include\s*["<]((?:%s)/[^">]+)[">]' % "|".join(map(re.escape, internal)))
    clients = [f for ext in ("cpp", "hpp") for f in glob.glob(os.path.join(root, "cli", "**", "*." + ext), recursive=True)]
    clients += glob.glob(os.path.join(root, "python", "*.cpp"))
    public = glob.glob(os.path.join(root, "src", "**", "include", "minksum", "*.hpp"), recursive=True)
    problems = []
    for kind, files in (("the command or the Python module", clients), ("a public header", public)):
        for path in sorted(files):
            with open(path, encoding="utf-8") as f:
                for n, line in enumerate(f, 1):
                    m = pattern.match(line)
                    if m:
                        problems.append(f"{os.path.relpath(path, root)}:{n}: {kind} includes the internal header "
                                        f"{m.group(1)}")
    if len(clients) < 10 or len(public) < 10:
        sys.exit(f"{root}: only {len(clients)} sources of cli/ and python/ and {len(public)} public headers found")
    if problems:
        print("\n".join(problems))
        sys.exit(1)
    print(f"{len(clients)} sources of cli/ and python/ and {len(public)} public headers include no internal header "
          f"(internal folders: {', '.join(internal)})")


if __name__ == "__main__":
    main()
