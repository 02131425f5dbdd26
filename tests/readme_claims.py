"""README's "What it does" and "What it does not do": every line points to
where it is shown (a docs section or a test file), and what it points to
exists: the file, and for a #fragment a heading of that file whose GitHub
anchor it is."""

import pathlib
import re
import sys


def anchor(heading):
    text = heading.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    found, fenced = set(), False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and line.startswith("#"):
            found.add(anchor(line.lstrip("#")))
    return found


def claim_lists(readme):
    """The bullets of the two lists, each joined into one line."""
    lists, current = {}, None
    for line in readme.splitlines():
        if line.startswith("What it does"):
            current = line
            lists[current] = []
        elif current and line.startswith("- "):
            lists[current].append(line[2:])
        elif current and line.startswith("  ") and lists[current]:
            lists[current][-1] += " " + line.strip()
        elif current and line.startswith("#"):
            current = None
    return lists


def main(root):
    root = pathlib.Path(root)
    readme = (root / "README.md").read_text(encoding="utf-8")
    lists = claim_lists(readme)
    errors = []
    if len(lists) != 2 or any(not bullets for bullets in lists.values()):
        errors.append(f"README: expected the two lists 'What it does' and 'What it does not do', found {list(lists)}")
    for title, bullets in lists.items():
        for bullet in bullets:
            links = re.findall(r"\]\(([^)]+)\)", bullet)
            targets = [l for l in links if l.startswith(("docs/", "tests/"))]
            if not targets:
                errors.append(f"README '{title}': no docs section or test named: {bullet[:70]}...")
            for target in targets:
                path, _, fragment = target.partition("#")
                if not (root / path).is_file():
                    errors.append(f"README '{title}': {target}: no file {path}")
                elif fragment and fragment not in anchors(root / path):
                    errors.append(f"README '{title}': {target}: {path} has no heading with anchor '{fragment}'")
    for e in errors:
        print(e)
    count = sum(len(b) for b in lists.values())
    print(f"{count} README claims checked, {len(errors)} problems")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1]))
