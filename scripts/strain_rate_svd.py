#!/usr/bin/env python3
# Smallest singular values of the discrete deviatoric strain rate D_h on a no-slip n x n box
# (docs/RHEOLOGY.md, "Cessation"): cell-only S (shear = mean of the 4 node shear rates, the
# paper), node shear, node copy only, and cell + node copies (half each, plastic_grid = cell_node).
# Usage: /usr/bin/python3 scripts/strain_rate_svd.py N   (N <= 32: dense SVD)
import numpy as np, sys
n=int(sys.argv[1]); h=1.0/n
# dofs: U[j,i] i=1..n-1, j=0..n-1 ; V[j,i] j=1..n-1, i=0..n-1
iu={}; k=0
for j in range(n):
    for i in range(1,n): iu[('u',j,i)]=k; k+=1
for j in range(1,n):
    for i in range(n): iu[('v',j,i)]=k; k+=1
N=k
def Uval(row,j,i,c):
    if 1<=i<=n-1 and 0<=j<=n-1: row[iu[('u',j,i)]]+=c
def Vval(row,j,i,c):
    if 1<=j<=n-1 and 0<=i<=n-1: row[iu[('v',j,i)]]+=c
def gamma(i,j):  # nodal du/dy+dv/dx, no-slip ghost mirror
    row=np.zeros(N)
    if (i in (0,n)) and (j in (0,n)): return row
    if j==0: Uval(row,0,i,2/h); return row if i not in (0,n) else row
    if j==n: Uval(row,n-1,i,-2/h); return row
    if i==0: Vval(row,j,0,2/h); return row
    if i==n: Vval(row,j,n-1,-2/h); return row
    Uval(row,j,i,1/h); Uval(row,j-1,i,-1/h); Vval(row,j,i,1/h); Vval(row,j,i-1,-1/h); return row
rows_dev=[]; rows_div=[]; rows_xy_cell=[]
for j in range(n):
    for i in range(n):
        dxx=np.zeros(N); Uval(dxx,j,i+1,1/h); Uval(dxx,j,i,-1/h)
        dyy=np.zeros(N); Vval(dyy,j+1,i,1/h); Vval(dyy,j,i,-1/h)
        rows_dev.append(0.5*(dxx-dyy)); rows_div.append(dxx+dyy)
        rows_xy_cell.append(0.125*(gamma(i,j)+gamma(i+1,j)+gamma(i,j+1)+gamma(i+1,j+1)))
rows_xy_node=[0.5*gamma(i,j) for j in range(n+1) for i in range(n+1)]
Ddev=np.array(rows_dev); Div=np.array(rows_div)
Dcell=np.vstack([Ddev,np.array(rows_xy_cell)])
Dnode=np.vstack([Ddev,np.array(rows_xy_node)])
Dd=Ddev.reshape(n,n,-1)
rows=[]
for j in range(n+1):
    for i in range(n+1):
        cs=[Dd[jj,ii] for jj in (j-1,j) for ii in (i-1,i) if 0<=jj<n and 0<=ii<n]
        rows.append(sum(cs)/len(cs))
Dv=np.vstack([np.array(rows),np.array(rows_xy_node)])
Dboth=np.vstack([np.sqrt(0.5)*Dcell,np.sqrt(0.5)*Dv])
for name,D in [('node copy only',Dv),('cell+node (1/2 each)',Dboth)]:
    s1=np.linalg.svd(D,compute_uv=False); print(n,name,'smallest sv',s1[-4:],'largest',s1[0])
for name,D in [('cell-only (paper)',Dcell),('node shear',Dnode)]:
    s1=np.linalg.svd(D,compute_uv=False); print(n,name,'smallest sv',s1[-4:],'largest',s1[0])
