# ccma bench: run in the output folder (gnuplot convergence_lm.gnuplot)
set terminal pngcairo size 1400,560 font 'sans,10' noenhanced
set output 'convergence_lm.png'
set multiplot layout 1,2 title 'ccma: one control step (10 mm + 0.005 rad), Levenberg-Marquardt outer loop'
set xlabel 'wall time [ms]'
set logscale y
set format y '1e%T'
set key top right
set grid
set ylabel 'objective O [m^2]'
plot '4dof_complete_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#eb6b23' title '4dof_complete', '4dof_differential_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#9e9518' title '4dof_differential', '4dof_reduced_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#86eb23' title '4dof_reduced', '6dof_asymmetric_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#189e22' title '6dof_asymmetric', '6dof_six_agents_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#23eba5' title '6dof_six_agents', '6dof_symmetric_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#18809e' title '6dof_symmetric', 'hybrid_ccma_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#234beb' title 'hybrid_ccma', 'planar_3rpr_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#4a189e' title 'planar_3rpr', 'stewart_gough_6ups_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#e023eb' title 'stewart_gough_6ups'
set ylabel 'end-effector error [m or rad]'
plot '4dof_complete_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#eb6b23' title '4dof_complete', '4dof_differential_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#9e9518' title '4dof_differential', '4dof_reduced_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#86eb23' title '4dof_reduced', '6dof_asymmetric_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#189e22' title '6dof_asymmetric', '6dof_six_agents_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#23eba5' title '6dof_six_agents', '6dof_symmetric_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#18809e' title '6dof_symmetric', 'hybrid_ccma_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#234beb' title 'hybrid_ccma', 'planar_3rpr_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#4a189e' title 'planar_3rpr', 'stewart_gough_6ups_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#e023eb' title 'stewart_gough_6ups'
unset multiplot
set output
set terminal svg size 1400,560 font 'sans,10' noenhanced background rgb 'white'
set output 'convergence_lm.svg'
set multiplot layout 1,2 title 'ccma: one control step (10 mm + 0.005 rad), Levenberg-Marquardt outer loop'
set xlabel 'wall time [ms]'
set logscale y
set format y '1e%T'
set key top right
set grid
set ylabel 'objective O [m^2]'
plot '4dof_complete_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#eb6b23' title '4dof_complete', '4dof_differential_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#9e9518' title '4dof_differential', '4dof_reduced_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#86eb23' title '4dof_reduced', '6dof_asymmetric_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#189e22' title '6dof_asymmetric', '6dof_six_agents_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#23eba5' title '6dof_six_agents', '6dof_symmetric_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#18809e' title '6dof_symmetric', 'hybrid_ccma_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#234beb' title 'hybrid_ccma', 'planar_3rpr_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#4a189e' title 'planar_3rpr', 'stewart_gough_6ups_convergence_lm.dat' using 1:2 with linespoints lw 2 lc rgb '#e023eb' title 'stewart_gough_6ups'
set ylabel 'end-effector error [m or rad]'
plot '4dof_complete_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#eb6b23' title '4dof_complete', '4dof_differential_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#9e9518' title '4dof_differential', '4dof_reduced_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#86eb23' title '4dof_reduced', '6dof_asymmetric_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#189e22' title '6dof_asymmetric', '6dof_six_agents_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#23eba5' title '6dof_six_agents', '6dof_symmetric_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#18809e' title '6dof_symmetric', 'hybrid_ccma_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#234beb' title 'hybrid_ccma', 'planar_3rpr_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#4a189e' title 'planar_3rpr', 'stewart_gough_6ups_convergence_lm.dat' using 1:3 with linespoints lw 2 lc rgb '#e023eb' title 'stewart_gough_6ups'
unset multiplot
set output
