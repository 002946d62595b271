set terminal pngcairo size 1400,560 font 'sans,11'
set output 'benchmarks/results/convergence_bfgs.png'
set multiplot layout 1,2 title 'ccma: one control step (10 mm + 0.005 rad), BFGS outer loop' noenhanced
set xlabel 'wall time [ms]'
set logscale y
set format y '1e%T'
set key top right
set grid
set ylabel 'objective O [m^2]'
plot 'benchmarks/results/4dof_complete_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '4dof_complete' noenhanced, 'benchmarks/results/4dof_reduced_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '4dof_reduced' noenhanced, 'benchmarks/results/6dof_asymmetric_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '6dof_asymmetric' noenhanced, 'benchmarks/results/6dof_six_agents_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '6dof_six_agents' noenhanced, 'benchmarks/results/6dof_symmetric_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '6dof_symmetric' noenhanced
set ylabel 'end-effector error [m or rad]'
plot 'benchmarks/results/4dof_complete_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '4dof_complete' noenhanced, 'benchmarks/results/4dof_reduced_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '4dof_reduced' noenhanced, 'benchmarks/results/6dof_asymmetric_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '6dof_asymmetric' noenhanced, 'benchmarks/results/6dof_six_agents_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '6dof_six_agents' noenhanced, 'benchmarks/results/6dof_symmetric_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '6dof_symmetric' noenhanced
unset multiplot
set output
set terminal svg size 1400,560 font 'sans,11'
set output 'benchmarks/results/convergence_bfgs.svg'
set multiplot layout 1,2 title 'ccma: one control step (10 mm + 0.005 rad), BFGS outer loop' noenhanced
set xlabel 'wall time [ms]'
set logscale y
set format y '1e%T'
set key top right
set grid
set ylabel 'objective O [m^2]'
plot 'benchmarks/results/4dof_complete_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '4dof_complete' noenhanced, 'benchmarks/results/4dof_reduced_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '4dof_reduced' noenhanced, 'benchmarks/results/6dof_asymmetric_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '6dof_asymmetric' noenhanced, 'benchmarks/results/6dof_six_agents_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '6dof_six_agents' noenhanced, 'benchmarks/results/6dof_symmetric_convergence_bfgs.dat' using 1:2 with linespoints lw 2 title '6dof_symmetric' noenhanced
set ylabel 'end-effector error [m or rad]'
plot 'benchmarks/results/4dof_complete_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '4dof_complete' noenhanced, 'benchmarks/results/4dof_reduced_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '4dof_reduced' noenhanced, 'benchmarks/results/6dof_asymmetric_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '6dof_asymmetric' noenhanced, 'benchmarks/results/6dof_six_agents_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '6dof_six_agents' noenhanced, 'benchmarks/results/6dof_symmetric_convergence_bfgs.dat' using 1:3 with linespoints lw 2 title '6dof_symmetric' noenhanced
unset multiplot
set output
