# Deflation (A-DEF2) with rigid-body modes of groups joined by blocks of Frobenius strength > theta.
from probe import *
run("IC", Mi)
for th in [0.3, 0.1, 0.03, 0.01, 0.003]:
    lab, R = components(frobenius, th); sizes = np.bincount(lab)
    for rot in [True, False]:
        Z = basis(lab, R, rot)
        if Z.size == 0:
            continue
        print(f"theta {th}: {np.sum(sizes > 1)} aggregates, largest {sizes.max()}, coarse {Z.shape[1]} rot {rot}", end="  ")
        run("adef2", adef2(Z), Z)
