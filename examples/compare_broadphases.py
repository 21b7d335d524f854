#!/usr/bin/python3
"""Every broad phase of deformcd's detector on the same frames, timed, and checked to agree.

Two icospheres made in NumPy slide through each other over N frames, the moving one wobbling
(a deformable body's surface, not a rigid one). One detector per broad phase, all on the CPU,
all reading the SAME float32 position arrays in place (set_positions keeps a reference and
copies nothing): each frame moves the arrays, then every detector's detect() is timed. The
script checks that every method finds exactly the contacts of "brute" (the all-pairs
baseline) at every frame, prints a table, and draws the time per frame of each method into a
PNG (matplotlib, Agg backend: no display needed). Each time is the fastest of --repeat passes
on the same positions (the minimum filters out other processes' noise).

    PYTHONPATH=build/release/python /usr/bin/python3 examples/compare_broadphases.py out.png
    ... --frames 30 --subdivisions 3 --threads 2

Exit status 1 when two methods disagree.
"""

import argparse
import statistics
import sys
import time

import numpy as np

import deformcd


def icosphere(subdivisions, radius=1.0):
    """A unit icosahedron subdivided `subdivisions` times, scaled to `radius`:
    (vertices float32 (n, 3), faces int64 (20 * 4**subdivisions, 3)), counter-clockwise
    seen from outside."""
    t = (1.0 + 5.0**0.5) / 2.0
    vertices = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0],
                [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
                [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11],
             [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
             [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9],
             [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    v = [np.array(p, dtype=np.float64) / np.linalg.norm(p) for p in vertices]
    for _ in range(subdivisions):
        midpoint = {}

        def middle(i, j):
            key = (min(i, j), max(i, j))
            if key not in midpoint:
                m = v[i] + v[j]
                v.append(m / np.linalg.norm(m))
                midpoint[key] = len(v) - 1
            return midpoint[key]

        next_faces = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            next_faces += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = next_faces
    return (np.array(v) * radius).astype(np.float32), np.array(faces, dtype=np.int64)


def sliding_pose(rest, frame, frames, out):
    """Writes into `out` (float32 (n, 3), in place) the moving sphere's pose at `frame` of
    `frames`: carried along x from -3.6 to +3.6 through the other sphere (at the origin),
    off-centre in y so that it crosses that sphere's surface all the way through, squashed and
    stretched by a wobble of about 8 %."""
    s = frame / max(frames - 1, 1)
    wobble = 1.0 + 0.08 * np.sin(2.0 * np.pi * 3.0 * s + 2.0 * rest[:, 0:1])
    out[:] = rest * wobble.astype(np.float32)
    out += np.array([-3.6 + 7.2 * s, 0.45, 0.07], dtype=np.float32)


def contact_key(c):
    """The contacts of a pass as one comparable array: (body_a, face_a, body_b, face_b) rows."""
    return np.stack([c["body_a"], c["face_a"], c["body_b"], c["face_b"]], axis=1)


def run(frames, subdivisions, threads, methods=deformcd.broadphases, repeat=1):
    """Times every method over the frames. Returns a dict: "ms" (per method, the detect() time
    of each frame, the minimum of `repeat` passes on the same positions), "contacts" (per frame, found by the first method), "disagreements"
    ((frame, method, contacts found, the first method's) tuples), "triangles" (per sphere) and
    "device" (the CPU backend's description)."""
    V0, F0 = icosphere(subdivisions, radius=1.0)
    rest1, F1 = icosphere(subdivisions, radius=0.7)
    V1 = rest1.copy()
    sliding_pose(rest1, 0, frames, V1)
    detectors = {}
    for method in methods:
        d = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu", broadphase=method,
                              threads=threads)
        assert d.positions(1) is V1  # float32 C-contiguous: read in place, not copied
        d.prepare()  # hierarchies built outside the timed passes
        detectors[method] = d
    result = {"ms": {method: [] for method in methods}, "contacts": [], "disagreements": [],
              "triangles": (len(F0), len(F1)), "device": detectors[methods[0]].device}
    for frame in range(frames):
        sliding_pose(rest1, frame, frames, V1)  # in place: every detector sees it
        reference = None
        for method, d in detectors.items():
            best = float("inf")
            for _ in range(repeat):
                start = time.perf_counter()
                d.detect()
                best = min(best, time.perf_counter() - start)
            result["ms"][method].append(1000.0 * best)
            key = contact_key(d.contacts())
            if reference is None:
                reference = key
                result["contacts"].append(len(key))
            elif not np.array_equal(key, reference):
                result["disagreements"].append((frame, method, len(key), len(reference)))
    return result


def median_in_contact(times, contacts):
    """The median over the frames with contacts (the costly ones), or None."""
    in_contact = [t for t, c in zip(times, contacts) if c > 0]
    return statistics.median(in_contact) if in_contact else None


def plot(path, result):
    """Time per frame per method (log scale) above the contacts per frame."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    contacts = result["contacts"]
    frames = np.arange(len(contacts))
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(11, 6.5), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
    colours = {"brute": "tab:red", "octree": "tab:orange", "octree-compact": "tab:green",
               "bvh": "tab:blue"}
    for method, times in result["ms"].items():
        label = f"{method}\nmedian {statistics.median(times):.3g} ms"
        touching = median_in_contact(times, contacts)
        if touching is not None:
            label += f",\n{touching:.3g} ms in contact"
        top.plot(frames, times, marker=".", markersize=4, linewidth=1.2,
                 color=colours.get(method), label=label)
    in_contact = np.asarray(contacts) > 0
    if in_contact.any():
        first, last = frames[in_contact][0], frames[in_contact][-1]
        for ax in (top, bottom):
            ax.axvspan(first - 0.5, last + 0.5, color="0.92", zorder=0)
        top.text((first + last) / 2, 0.02, "spheres in contact",
                 transform=top.get_xaxis_transform(), ha="center", va="bottom", color="0.4")
    top.set_yscale("log")
    top.set_ylabel("detect() wall time per frame\n(ms, fastest of the repeats, log scale)")
    triangles = result["triangles"]
    top.set_title(f"deformcd Detector.detect() per frame, each broad phase ({result['device']})\n"
                  f"two icospheres of {triangles[0]:,} and {triangles[1]:,} triangles sliding "
                  f"through each other, the moving one wobbling", fontsize=11)
    top.grid(True, which="both", alpha=0.3)
    top.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=9, labelspacing=1.0,
               title="broad phase")
    bottom.bar(frames, contacts, width=0.9, color="0.35")
    bottom.set_ylabel("contacts\n(triangle pairs)")
    bottom.set_xlabel("frame")
    bottom.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("png", help="where to write the chart (PNG)")
    parser.add_argument("--frames", type=int, default=60, help="frames (default 60)")
    parser.add_argument("--subdivisions", type=int, default=4,
                        help="icosphere subdivisions: 20 x 4^S triangles each (default 4: 5,120)")
    parser.add_argument("--threads", type=int, default=0, help="CPU threads (0: every core)")
    parser.add_argument("--repeat", type=int, default=3,
                        help="passes per frame and method, the fastest kept (default 3)")
    parser.add_argument("--methods", default=",".join(deformcd.broadphases),
                        help="comma-separated broad phases, the first the reference "
                             "(default: all, brute first)")
    args = parser.parse_args(argv)
    if args.frames < 1 or args.subdivisions < 0 or args.repeat < 1:
        parser.error("--frames and --repeat must be at least 1, --subdivisions at least 0")
    methods = args.methods.split(",")

    result = run(args.frames, args.subdivisions, args.threads, methods, args.repeat)
    contacts = result["contacts"]
    triangles = result["triangles"]
    print(f"{triangles[0]} + {triangles[1]} triangles, {args.frames} frames, "
          f"{result['device']}; {sum(c > 0 for c in contacts)} frames in contact, "
          f"up to {max(contacts)} contacts in a frame")
    print(f"{'method':<16}{'median ms':>10}{'in contact':>12}{'max ms':>10}{'total s':>10}")
    for method, times in result["ms"].items():
        touching = median_in_contact(times, contacts)
        touching = f"{touching:>12.3f}" if touching is not None else f"{'-':>12}"
        print(f"{method:<16}{statistics.median(times):>10.3f}{touching}{max(times):>10.3f}"
              f"{sum(times) / 1000:>10.3f}")
    plot(args.png, result)
    print(f"chart: {args.png}")
    if result["disagreements"]:
        for frame, method, got, expected in result["disagreements"][:10]:
            print(f"frame {frame}: {method} found {got} contacts, {methods[0]} {expected}",
                  file=sys.stderr)
        return 1
    print(f"every method found the same contacts as {methods[0]} at every frame")
    return 0


if __name__ == "__main__":
    sys.exit(main())
