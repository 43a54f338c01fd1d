(define (problem lander-09)
  (:domain lander)
  (:init
    (flying)
    (= (h) 4048.4) (= (v) -70)
    (= (mass) 1163.49) (= (fuel) 163.49) (= (burn-rate) 5)
    (= (gravity) 3.71) (= (thrust) 9064.8)
    (= (touch-height) 0.6) (= (safe-speed) 1))
  (:goal (and (landed))))
