# Deflation (A-DEF2) with rigid-body modes of groups joined by blocks of StiffClusterFill's trace
# ratio > theta, groups of at least `mn` bodies.
from probe import *
for th in [0.4, 0.3, 0.2]:
    lab, R = components(ratio, th); sz = np.bincount(lab)
    for mn in [3, 5, 8]:
        for rot in [False, True]:
            Z = basis(lab, R, rot, minsize=mn)
            print(f"ratio>{th} size>={mn} rot {rot}: {Z.shape[1]} coarse dofs, largest agg {sz.max()}", end=" ")
            run("adef2", adef2(Z), Z)
