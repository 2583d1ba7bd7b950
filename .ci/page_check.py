"""Open a page of hpr-mc's (a run's report.html, a flight plot) in headless Chromium, take a
screenshot and check that it rendered: no console message (the pages have no script, so any
is an error), and charts drawn (enough pixels of the charts' blue, orange and green, in more
than one place down the page).

usage: page_check.py PAGE.html SCREENSHOT.png HEIGHT_PX [LEAST_BLUE_SHARE]
(LEAST_BLUE_SHARE: the least share of the screenshot's pixels in the charts' blue, default
0.01; a page of thin lines has less than a page of bars.)
"""

import os
import shutil
import subprocess
import sys
import tempfile

from PIL import Image

PALETTE = {"blue": (0x00, 0x72, 0xB2), "orange": (0xD5, 0x5E, 0x00), "green": (0x00, 0x9E, 0x73)}


def near(p, c, tol=40):
    return all(abs(a - b) <= tol for a, b in zip(p, c))


def main():
    page, shot, height = sys.argv[1], sys.argv[2], int(sys.argv[3])
    least_blue = float(sys.argv[4]) if len(sys.argv) > 4 else 0.01
    profile = tempfile.mkdtemp(prefix="hpr-mc-chromium-")
    try:
        run = subprocess.run(
            [
                "chromium", "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                "--no-first-run", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", f"--user-data-dir={profile}",
                "--hide-scrollbars", "--enable-logging=stderr", "--v=0",
                f"--window-size=1240,{height}", f"--screenshot={shot}",
                "file://" + os.path.abspath(page),
            ],
            capture_output=True, text=True, timeout=180,
        )
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    console = [l for l in run.stderr.splitlines() if ":CONSOLE" in l]
    if console:
        sys.exit(f"{page}: console messages:\n" + "\n".join(console))
    if not os.path.isfile(shot):
        sys.exit(f"{page}: no screenshot ({run.returncode}):\n{run.stderr[-2000:]}")
    im = Image.open(shot).convert("RGB")
    w, h = im.size
    px = im.load()
    counts = {k: 0 for k in PALETTE}
    bands = {k: set() for k in PALETTE}
    for y in range(0, h, 2):
        for x in range(0, w, 2):
            p = px[x, y]
            for k, c in PALETTE.items():
                if near(p, c):
                    counts[k] += 1
                    bands[k].add(y // 400)
    total = (w // 2) * (h // 2)
    print(
        f"{page}: {w}×{h} px screenshot {shot}; chart pixels "
        + ", ".join(f"{k} {100 * counts[k] / total:.2f} % in {len(bands[k])} bands" for k in PALETTE)
    )
    if counts["blue"] < least_blue * total or len(bands["blue"]) < 3:
        sys.exit(f"{page}: the charts look blank (too little of the charts' blue)")
    if counts["orange"] == 0:
        sys.exit(f"{page}: no orange: a chart's second series is missing")


if __name__ == "__main__":
    main()
