set terminal pngcairo size 1600,1520 font 'sans,9'
set output 'docs/bench/error_vs_time.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key bottom left
set multiplot layout 4,4 title 'relative RMSE of pixel irradiance against wall time (trace + resolve)'
set title 'point_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_0 << EOD
0.000873246 2.48151
0.00105898 0.814132
0.00273939 0.250412
0.0193007 0.0737579
0.190728 0.0242166
1.85321 0.00768919
EOD
$d1_0 << EOD
0.00035017 2.48151
0.000920846 0.814132
0.00621755 0.250412
0.0339517 0.0737579
0.310783 0.0242166
2.85182 0.00768918
EOD
plot $d0_0 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_0 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00768919*(x/1.85321)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'point_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_1 << EOD
0.00163051 3.13913
0.00138514 1.24226
0.00422863 0.386499
0.0306609 0.127715
0.184145 0.039639
1.81903 0.0126134
EOD
$d1_1 << EOD
0.000286716 3.13913
0.00078879 1.24226
0.00366764 0.386499
0.0277116 0.127715
0.271969 0.039639
2.44645 0.0126134
EOD
plot $d0_1 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_1 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.0126134*(x/1.81903)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_2 << EOD
0.00104344 1.43653
0.00130465 0.481258
0.00343493 0.160017
0.0230917 0.0486866
0.236595 0.0149436
2.36056 0.00500333
EOD
$d1_2 << EOD
0.000214768 1.43653
0.00082235 0.481258
0.00500081 0.160017
0.0426254 0.0486866
0.413365 0.0149436
4.14305 0.00500333
EOD
plot $d0_2 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_2 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00500333*(x/2.36056)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_3 << EOD
0.00104588 2.09389
0.00155076 0.610668
0.0042874 0.184784
0.0245887 0.0576963
0.232344 0.0187082
2.34432 0.00605956
EOD
$d1_3 << EOD
0.000180518 2.09389
0.00077437 0.610668
0.00490576 0.184784
0.0475868 0.0576963
0.477839 0.0187082
3.93662 0.00605956
EOD
plot $d0_3 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_3 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00605956*(x/2.34432)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'furnace' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_4 << EOD
0.000717544 2.15149
0.000894557 0.705714
0.00441284 0.223067
0.0194906 0.0688873
0.211616 0.0237385
1.77018 0.0066814
EOD
$d1_4 << EOD
0.000157554 2.15149
0.00363647 0.705714
0.00591672 0.223067
0.0375789 0.0688873
0.308436 0.0237385
3.00693 0.0066814
EOD
plot $d0_4 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_4 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.0066814*(x/1.77018)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_d65' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_5 << EOD
0.00218461 0.594722
0.00244551 0.203314
0.00444711 0.0611355
0.0256153 0.0189767
0.232411 0.00615257
2.18559 0.00196103
EOD
$d1_5 << EOD
0.000111876 0.594722
0.000581913 0.203314
0.00403385 0.0611355
0.0317938 0.0189767
0.319676 0.00615257
3.69582 0.00196104
EOD
plot $d0_5 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_5 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/2.18559)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_a' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_6 << EOD
0.00223535 0.594722
0.0023464 0.203314
0.00505392 0.0611355
0.0266715 0.0189767
0.234704 0.00615257
2.14739 0.00196103
EOD
$d1_6 << EOD
0.000180568 0.594722
0.000932254 0.203314
0.00553914 0.0611355
0.0372723 0.0189767
0.382904 0.00615257
3.88684 0.00196104
EOD
plot $d0_6 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_6 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/2.14739)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f2' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_7 << EOD
0.0020537 0.594722
0.0022879 0.203314
0.00462329 0.0611355
0.0278363 0.0189767
0.264332 0.00615257
2.56678 0.00196103
EOD
$d1_7 << EOD
0.000166187 0.594722
0.00086314 0.203314
0.00580127 0.0611355
0.036987 0.0189767
0.370195 0.00615257
3.79216 0.00196103
EOD
plot $d0_7 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_7 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/2.56678)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f11' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_8 << EOD
0.0017286 0.594722
0.00180814 0.203314
0.0040841 0.0611355
0.0274143 0.0189767
0.256687 0.00615257
2.608 0.00196103
EOD
$d1_8 << EOD
0.000166908 0.594722
0.000877572 0.203314
0.00698817 0.0611355
0.038906 0.0189767
0.37439 0.00615257
3.69385 0.00196103
EOD
plot $d0_8 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_8 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/2.608)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_led_b3' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_9 << EOD
0.0018628 0.594722
0.00209564 0.203314
0.00454278 0.0611355
0.0278896 0.0189767
0.259971 0.00615257
2.26607 0.00196103
EOD
$d1_9 << EOD
0.000178335 0.594722
0.000881879 0.203314
0.00572631 0.0611355
0.0367389 0.0189767
0.383368 0.00615257
3.24149 0.00196103
EOD
plot $d0_9 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_9 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00196103*(x/2.26607)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'laser_532' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_10 << EOD
0.000831084 0.73791
0.00117116 0.23595
0.0028118 0.0767803
0.0223863 0.023128
0.24439 0.00729035
2.15361 0.00237266
EOD
$d1_10 << EOD
0.000102251 0.73791
0.000566841 0.23595
0.00406876 0.0767803
0.0366191 0.023128
0.348307 0.00729035
3.42675 0.00237266
EOD
plot $d0_10 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_10 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00237266*(x/2.15361)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_rect' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_11 << EOD
0.00341088 0.661868
0.00408032 0.230997
0.00765573 0.0636716
0.0415411 0.020916
0.378916 0.00644784
3.71866 0.00203705
EOD
$d1_11 << EOD
0.000274698 0.661868
0.00100223 0.230997
0.0066705 0.0636716
0.060547 0.020916
0.601606 0.00644784
6.11476 0.00203705
EOD
plot $d0_11 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_11 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00203705*(x/3.71866)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_small' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_12 << EOD
0.00319276 0.831923
0.00338352 0.268993
0.00633973 0.0822313
0.0372283 0.025986
0.353113 0.00857101
3.50285 0.00284146
EOD
$d1_12 << EOD
0.000171505 0.831923
0.000859475 0.268993
0.00633691 0.0822313
0.0560647 0.025986
0.549425 0.00857101
5.32181 0.00284147
EOD
plot $d0_12 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_12 with linespoints lw 2 title 'CPU reference, 2 threads, x86-64-v3' noenhanced, 0.00284146*(x/3.50285)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
unset multiplot
