import numpy as np
from load import *
exec(open('defl.py').read().split("run(\"IC\"")[0])
U=np.load('/work/runs/defl/U40.npy'); ev=np.load('/work/runs/defl/ev.npy')
for k in range(12):
    u=U[:,k].reshape(N,6); w=(u**2).sum(1); w/=w.sum()
    pr=1/(w**2).sum()
    top=np.argsort(-w)[:8]
    tr=(u[:,:3]**2).sum()/(u**2).sum()
    print(f"ev {ev[k]:.4f} participation {pr:.1f} bodies, translation share {tr:.2f}, top bodies {top} weights {np.round(w[top],3)}")
# deflate exact eigenvectors
for k in [2,5,12,26,40]:
    Z=U[:,:k]; print("exact eigvecs",k,end=" "); run("adef2",adef2(Z),Z)
