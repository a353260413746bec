from load import *
n,tol,A,b,x0,Minv=load()
Ms=(Minv+Minv.T)/2
C=np.linalg.cholesky(Ms)
ev,V=np.linalg.eigh(C.T@A@C)
U=C@V[:,:40]
np.save('/work/runs/defl/U40.npy',U); np.save('/work/runs/defl/ev.npy',ev)
print("done")
