import sys, numpy as np
from load import *
n,tol,A,b,x0,Minv=load(); N=n//6
pos,L,strain=positions(); off=(strain*L)%L
Mi=lambda r: Minv@r
# body-block strengths
Ab=A.reshape(N,6,N,6).transpose(0,2,1,3)
nrm=np.linalg.norm(Ab,axis=(2,3))
d=np.sqrt(np.diag(nrm)); S=nrm/np.outer(d,d); np.fill_diagonal(S,0)
def rel(i,j):
    v=pos[j]-pos[i]; ny=np.round(v[1]/L); v[1]-=ny*L; v[0]-=ny*off; v[0]-=L*np.round(v[0]/L); v[2]-=L*np.round(v[2]/L); return v
def components(theta, maxsize=10**9):
    lab=-np.ones(N,int); c=0; R=np.zeros((N,3))
    for s in range(N):
        if lab[s]>=0: continue
        lab[s]=c; R[s]=0; st=[s]; size=1
        while st:
            i=st.pop()
            for j in np.nonzero(S[i]>theta)[0]:
                if lab[j]<0 and size<maxsize: lab[j]=c; R[j]=R[i]+rel(i,j); st.append(j); size+=1
        c+=1
    return lab,R
def basis(lab,R,rot=True,minsize=2):
    cols=[]
    for c in range(lab.max()+1):
        m=np.nonzero(lab==c)[0]
        if len(m)<minsize: continue
        X=R[m].mean(0)
        for k in range(3):
            z=np.zeros(n); z[6*m+k]=1; cols.append(z)
        if rot:
            for k in range(3):
                e=np.zeros(3); e[k]=1; z=np.zeros(n)
                for i in m: z[6*i:6*i+3]=np.cross(e,R[i]-X); z[6*i+3+k]=1
                cols.append(z)
    return np.array(cols).T
def adef2(Z):
    AZ=A@Z; E=Z.T@AZ; Ei=np.linalg.inv(E)
    def prec(r):
        s=Mi(r); return s+Z@(Ei@(Z.T@r-AZ.T@s))
    return prec
def additive(Z):
    AZ=A@Z; E=Z.T@AZ; Ei=np.linalg.inv(E)
    return lambda r: Mi(r)+Z@(Ei@(Z.T@r))
def run(name,prec,Z=None):
    xs=x0.copy()
    if Z is not None:  # start consistent for A-DEF2: x = Q b + P^T x0
        AZ=A@Z; Ei=np.linalg.inv(Z.T@AZ); xs = xs + Z@(Ei@(Z.T@(b-A@xs)))
    xw,itw=pcg(A,b,xs,prec,tol)
    xc,itc=pcg(A,b,np.zeros(n) if Z is None else Z@(np.linalg.inv(Z.T@A@Z)@(Z.T@b)),prec,tol)
    print(f"{name}: warm {itw} cold {itc}", flush=True)
run("IC", Mi)
for th in [0.3,0.1,0.03,0.01,0.003]:
    lab,R=components(th); sizes=np.bincount(lab)
    for rot in [True,False]:
        Z=basis(lab,R,rot)
        if Z.size==0: continue
        print(f"theta {th}: {np.sum(sizes>1)} aggregates, largest {sizes.max()}, coarse {Z.shape[1]} rot {rot}", end="  ")
        run("adef2", adef2(Z), Z)
