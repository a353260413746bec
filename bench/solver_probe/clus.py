# Which stiff clusters (StiffClusterFill's rule: trace ratio > 0.5) the lowest modes sit on.
from probe import *
U = np.load(OUT + "/U40.npy"); ev = np.load(OUT + "/ev.npy")
lab = components(ratio, 0.5)[0]; sz = np.bincount(lab)
print("clusters >=3:", (sz >= 3).sum(), "sizes hist", np.bincount(sz)[:30], "largest", sz.max())
for k in range(6):
    u = U[:, k].reshape(N, 6); w = (u ** 2).sum(1); w /= w.sum(); top = np.argsort(-w)[:6]
    print(f"mode {k} ev {ev[k]:.3f}: clusters of top bodies {lab[top]} sizes {sz[lab[top]]}")
    print(np.round(ratio[np.ix_(top, top)], 2))
