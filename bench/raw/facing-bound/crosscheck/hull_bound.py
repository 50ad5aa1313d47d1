# The cross-check of bench/facing_bound (RESULTS section 35): see README.md beside it.
# For each audible source: in its facing frame (yaw to the source, pitch 0, 90 deg hfov, 16:9),
# the smallest angle error any weighted centroid of the visible spots could reach
# (the source's point inside their convex hull -> 0), and the share within 15 deg.
import csv, json, math, re, subprocess, sys
binary, scene, csvp = sys.argv[1:4]
info = subprocess.run([binary, 'info', scene], capture_output=True, text=True).stdout
src, lis = {}, None
for line in info.splitlines():
    m = re.match(r'\s+(\d+) \S+\s+\S+\s+at \(([^)]*)\)', line)
    if m: src[int(m.group(1))] = [float(x) for x in m.group(2).split(',')]
    m = re.match(r'listener: \(([^)]*)\)', line)
    if m: lis = [float(x) for x in m.group(1).split(',')]
th = math.tan(math.radians(45)); tv = th * 720 / 1280
def frame(s):
    d = [src[s][i] - lis[i] for i in range(3)]
    yaw = math.atan2(d[0], -d[2])  # forward -z at yaw 0 (glTF camera), right +x
    f = (math.sin(yaw), 0.0, -math.cos(yaw)); r = (math.cos(yaw), 0.0, math.sin(yaw)); u = (0.0, 1.0, 0.0)
    return f, r, u, d
def proj(v, fr):
    f, r, u, _ = fr
    z = sum(a*b for a, b in zip(v, f))
    if z <= 1e-6: return None
    x = sum(a*b for a, b in zip(v, r)) / z / th; y = sum(a*b for a, b in zip(v, u)) / z / tv
    if abs(x) > 1 or abs(y) > 1: return None
    return (x, y)
def err(p, fr):
    f, r, u, d = fr
    v = [f[i] + p[0]*th*r[i] + p[1]*tv*u[i] for i in range(3)]
    nv = math.sqrt(sum(a*a for a in v)); nd = math.sqrt(sum(a*a for a in d))
    return math.degrees(math.acos(max(-1, min(1, sum(a*b for a, b in zip(v, d)) / nv / nd))))
def hull(pts):
    pts = sorted(set(pts))
    if len(pts) <= 2: return pts
    def cross(o, a, b): return (a[0]-o[0])*(b[1]-o[1]) - (a[1]-o[1])*(b[0]-o[0])
    lo, up = [], []
    for p in pts:
        while len(lo) >= 2 and cross(lo[-2], lo[-1], p) <= 0: lo.pop()
        lo.append(p)
    for p in reversed(pts):
        while len(up) >= 2 and cross(up[-2], up[-1], p) <= 0: up.pop()
        up.append(p)
    return lo[:-1] + up[:-1]
frames = {s: frame(s) for s in src}
pts = {s: [] for s in src}
for row in csv.DictReader(open(csvp)):
    if float(row['heard']) <= 0: continue
    s = int(row['source']); p = [float(row[k]) for k in ('x', 'y', 'z')]
    q = proj([p[i] - lis[i] for i in range(3)], frames[s])
    if q: pts[s].append((round(q[0], 4), round(q[1], 4)))
for s in sorted(src):
    dist = math.dist(src[s], lis)
    if dist > 30.0: continue
    P = pts[s]
    if not P:
        print(scene.split('/')[-1], s, f"{dist:5.1f}m", "in-frame visible 0  best -"); continue
    H = hull(P)
    # source's own point: x = 0, y = tan(el)/tv (may be outside the frame)
    fr = frames[s]; d = fr[3]
    el = math.atan2(d[1], math.hypot(d[0], d[2])); sp = (0.0, math.tan(el) / tv)
    inside = len(H) >= 3 and all(((H[(i+1) % len(H)][0]-H[i][0])*(sp[1]-H[i][1]) - (H[(i+1) % len(H)][1]-H[i][1])*(sp[0]-H[i][0])) >= 0 for i in range(len(H)))
    best = 0.0 if inside else min(err((a[0]+(b[0]-a[0])*t/64, a[1]+(b[1]-a[1])*t/64), fr)
                                   for a, b in zip(H, H[1:]+H[:1]) for t in range(65))
    le15 = sum(1 for p in P if err(p, fr) <= 15) if len(P) < 200000 else -1
    print(scene.split('/')[-1], s, f"{dist:5.1f}m", f"in-frame visible {len(P)} le15 {le15} best {best:.1f}")
