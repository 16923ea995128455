"""Self-contact in scenes (issue 12; tests/self_contact_block.prm,
tests/self_contact_strip.prm).

 - A block squashed by 30 % with a self-contact pair on its whole boundary
   (Slave = Master = left, right, bottom, top): its sides barrel and its
   corners fold, yet no node ever touches its own surface (flat sides), and
   none either when the block's sides are arcs (gently curved surfaces).
 - A strip bent into a hairpin whose upper leg is pressed onto the lower leg
   (Slave = Master = bottom, the inner skin): it touches itself; the two sides
   of the fold press on each other alike: each node of either side is a slave
   of the other side's faces (two-pass, half penalties), so the sum of the
   forces on all slave nodes, sum over the upper side (down) plus sum over the
   lower side (up), vanishes when the pressures balance, whatever the total;
   the global balance of the strip: the contact is internal, so the reaction
   of the pushed end equals minus that of the clamped one; no penetration
   beyond the limit (half the shortest contact edge, 0.25 mm); np = 2 gives
   the same forces as np = 1.
"""
from anvil_test import run, read_csv, check, close, finish

for name, sets in (("flat", []),
                   ("curved", ["Geometry/Transformation=x + 0.04*(y - 5)^2, y"])):
    out, s, _ = run("tests/self_contact_block.prm", sets, name="self_contact_block_" + name)
    c = read_csv(out + "/contact.csv")
    r = read_csv(out + "/reactions.csv")
    print("  %s block squashed by 30 %%: %d steps, top force %.1f N/mm at the end" % (
        name, len(c["time"]), s["quantities_of_interest"]["force"]))
    check(c["time"][-1] > 1 - 1e-9, "%s block: squashed by 30 %% (t = %g)" % (name, c["time"][-1]))
    check(max(c["skin_active_nodes"]) == 0,
          "%s block: no self-contact node at any step (largest count %d, expected 0)"
          % (name, max(c["skin_active_nodes"])))

limit = 0.25  # half the shortest contact edge (0.5 mm through the thickness)
results = {}
for np in (1, 2):
    out, s, _ = run("tests/self_contact_strip.prm", np=np, name="self_contact_strip_np%d" % np)
    results[np] = (read_csv(out + "/contact.csv"), read_csv(out + "/reactions.csv"), s)
c, r, s = results[1]
last = len(c["time"]) - 1
N, Fy = c["fold_normal"][last], c["fold_Fy"][last]
print("  strip: %d active nodes, sum t_N = %.3f N/mm, sum of forces on the slave nodes (%.3e, %.3e) N/mm, "
      "max penetration %.4f mm" % (c["fold_active_nodes"][last], N, c["fold_Fx"][last], Fy,
                                   c["fold_max_penetration"][last]))
check(c["fold_active_nodes"][last] >= 4, "the strip touches itself (%d nodes)" % c["fold_active_nodes"][last])
check(N > 10, "with a force (sum t_N = %.2f N/mm)" % N)
# Each side's nodes press on the other side's faces with half the penalty; the
# two sums differ only by the nodes at the edges of the contact zone (one side
# may have one more node inside it), so the imbalance is at most the largest
# force one node carries, c_N/2 x the largest penetration.
node_force = 0.5 * 1e4 * c["fold_max_penetration"][last]
check(abs(Fy) <= node_force, "pressure balance: |sum of the slave forces, y| = %.3g N/mm (%.1f %% of sum t_N), "
      "at most one edge node's force c_N/2 g_max = %.3g" % (abs(Fy), 100 * abs(Fy) / N, node_force))
close(c["support_Fy"][last], -c["pressing_Fy"][last], 2e-2, "floor force = press force (the fold carries "
      "the press onto the lower leg; the clamp takes the rest)")
check(max(c["fold_max_penetration"]) <= limit,
      "no penetration beyond the limit: %.4f <= %.2f mm" % (max(c["fold_max_penetration"]), limit))
print("  reactions: %s" % ", ".join("%s %.4f" % (k, r[k][-1]) for k in r if k.endswith("_Fy")))
print("  press %.2f N/mm, floor %.2f N/mm, clamp %.2f N/mm" % (c["pressing_Fy"][last], c["support_Fy"][last],
                                                          r["left_Fy"][-1]))
close(c["pressing_Fy"][last] + c["support_Fy"][last] + r["left_Fy"][-1], 0, 0, "global balance: press + floor + "
      "clamp = 0 (the self-contact is internal)", atol=1e-6 * abs(c["pressing_Fy"][last]))
c2 = results[2][0]
for col in ("fold_normal", "fold_Fy", "fold_active_nodes", "fold_max_penetration"):
    diff = max(abs(a - b) for a, b in zip(c[col], c2[col]))
    scale = max(abs(a) for a in c[col]) or 1
    check(len(c[col]) == len(c2[col]) and diff <= 1e-8 * scale,
          "np = 2 equals np = 1: %s (largest difference %.3g)" % (col, diff))

# 3D: the plate folded onto itself, per mm of its 2 mm width against the strip,
# both at the default free-end taper: the strip's end segment and the plate's
# free facet edge are extended and tapered alike (doc/contact.md, "Free
# ends"), and a fold node is carried beyond the free end (the strip's fold
# force is 812.0166 N/mm tapered against 812.0052 sharp).
width = 2.0
out, _, _ = run("tests/self_contact_strip.prm", ["Mechanics/Element=standard", "Time/Time step=0.025",
                                                 "Time/Maximum time step=0.025"], name="self_contact_strip_q1")
cq = read_csv(out + "/contact.csv")
plate = {}
for np in (1, 2):
    out, s3, _ = run("tests/self_contact_plate_3d.prm", np=np, name="self_contact_plate_3d_np%d" % np)
    plate[np] = (read_csv(out + "/contact.csv"), read_csv(out + "/reactions.csv"), s3)
c3, r3, s3 = plate[1]
k = len(c3["time"]) - 1
kq = len(cq["time"]) - 1
print("  plate (3D): %d steps, %d active nodes, sum t_N = %.3f N (%.3f N/mm; strip %.3f N/mm), max penetration "
      "%.4f mm" % (len(c3["time"]), c3["fold_active_nodes"][k], c3["fold_normal"][k], c3["fold_normal"][k] / width,
                   cq["fold_normal"][kq], c3["fold_max_penetration"][k]))
check(len(c3["time"]) == len(cq["time"]), "3D plate and strip march the same steps (%d, %d)"
      % (len(c3["time"]), len(cq["time"])))
check(c3["time"][-1] > 1 - 1e-9 and c3["fold_active_nodes"][k] >= 8,
      "3D plate folded onto itself: touches itself (%d nodes)" % c3["fold_active_nodes"][k])
for col in ("fold_normal", "pressing_Fy", "support_Fy"):
    close(c3[col][k] / width, cq[col][kq], 1e-8, "3D plate = plane-strain strip, %s per mm of width" % col,
          atol=1e-8 * cq["fold_normal"][kq])
close(c3["fold_max_penetration"][k], cq["fold_max_penetration"][kq], 1e-8, "3D plate = strip: largest penetration")
node_force3 = 0.5 * 1e4 * c3["fold_max_penetration"][k] * 2   # an edge row: two nodes across the width
check(abs(c3["fold_Fy"][k]) <= node_force3, "3D pressure balance: |sum of the slave forces, y| = %.3g N, at most "
      "one edge row's force %.3g N" % (abs(c3["fold_Fy"][k]), node_force3))
close(c3["pressing_Fy"][k] + c3["support_Fy"][k] + r3["left_Fy"][-1], 0, 0, "3D global balance: press + floor "
      "+ clamp = 0", atol=1e-6 * abs(c3["pressing_Fy"][k]))
check(max(c3["fold_max_penetration"]) <= limit, "3D: no penetration beyond the limit: %.4f <= %.2f mm"
      % (max(c3["fold_max_penetration"]), limit))
c32 = plate[2][0]
for col in ("fold_normal", "fold_Fy", "fold_active_nodes", "fold_max_penetration"):
    diff = max(abs(a - b) for a, b in zip(c3[col], c32[col]))
    scale = max(abs(a) for a in c3[col]) or 1
    check(len(c3[col]) == len(c32[col]) and diff <= 1e-8 * scale,
          "3D np = 2 equals np = 1: %s (largest difference %.3g)" % (col, diff))
finish()
