#!/usr/bin/python3
"""The six SPD images of `bvhlab spd` on one sheet (docs/spd.md), three by two, half size.

    /usr/bin/python3 docs/plots/spd_sheet.py [--data out/spd] [--accel sahbvh8] [--out docs/images/spd_sheet.png]

Debian's python3-matplotlib (setup.sh installs it), through /usr/bin/python3.
"""
import argparse
import os

import matplotlib.image as mpimg
import numpy as np

SCENES = ["balls", "mount", "rings", "teapot", "tetra", "tree"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--data", default="out/spd", help="the --out folder of bvhlab spd")
    parser.add_argument("--accel", default="sahbvh8", help="whose images (SCENE.ACCEL.png)")
    parser.add_argument("--out", default="docs/images/spd_sheet.png")
    args = parser.parse_args()
    tiles = []
    for scene in SCENES:
        image = mpimg.imread(os.path.join(args.data, f"{scene}.{args.accel}.png"))[:, :, :3]
        tiles.append(image[::2, ::2])  # half size: every other pixel
    rows = [np.concatenate(tiles[i:i + 3], axis=1) for i in (0, 3)]
    mpimg.imsave(args.out, np.concatenate(rows, axis=0))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
