#!/bin/bash
# Example Slurm job for fastcontact on a cluster (doc/parallel.md).  Adapt partition,
# account, modules and paths to your site.  Three uses, pick one at the bottom:
#   A. MPI batch: the cases of a namelist file spread over all ranks (one core each);
#   B. distributed solve of one very large rough-surface cell (FFTW-MPI slabs, --distributed);
#   C. a job array of serial drivers sharing one file (--part), no MPI.
# A and C take --resume: resubmitted after the time limit, they skip the cases finished
# with the same input and solve the rest.
#SBATCH --job-name=fastcontact
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32
#SBATCH --cpus-per-task=1
#SBATCH --mem-per-cpu=3G
#SBATCH --time=01:00:00
#SBATCH --output=fastcontact-%j.out
set -euo pipefail

# module load gcc openmpi fftw     # site specific: Open MPI and FFTW built with the same MPI
export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}   # threads per rank (hybrid: raise cpus-per-task)
FC_MPI=${FC_MPI:-$HOME/.local/bin/fastcontact-mpi}
FC_BENCH=${FC_BENCH:-$HOME/.local/bin/fastcontact-mpi-bench}

# A. a creep-force map or parameter sweep: one namelist file, one output directory (a fixed
#    name, so that a resubmitted job with --resume finds the cases already done)
srun "$FC_MPI" sweep.nml --out results --resume

# B. one periodic rough-surface cell solved by all ranks together: a namelist as
#    mpi/example/rough_cell.nml with nx = ny = 16384 (memory model: ~15 MB + 130 B x 16384^2
#    / ranks per rank, i.e. ~0.55 GB/rank on 64 ranks); the element table alone is ~30 GB of
#    text, so give &output table = .false. unless it is wanted
# srun "$FC_MPI" cell16384.nml --distributed --out "cell-$SLURM_JOB_ID"
#    or the benchmark program on a generated cell:
# srun "$FC_BENCH" --n 16384 --case periodic --csv "cell-$SLURM_JOB_ID.csv"

# C. the same sweep as a job array of serial drivers, no MPI (submit with, e.g.,
#    sbatch --array=0-31 --nodes=1 --ntasks=1 slurm_fastcontact.sh): task K of N solves
#    cases K+1, K+1+N, ... of the file into one shared directory
# FC=${FC:-$HOME/.local/bin/fastcontact}
# "$FC" sweep.nml --part "$((SLURM_ARRAY_TASK_ID + 1))/$SLURM_ARRAY_TASK_COUNT" --out results --resume
