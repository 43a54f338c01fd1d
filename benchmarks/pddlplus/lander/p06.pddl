(define (problem lander-06)
  (:domain lander)
  (:init
    (flying)
    (= (h) 1527.6) (= (v) -40)
    (= (mass) 1102.14) (= (fuel) 102.14) (= (burn-rate) 5)
    (= (gravity) 3.71) (= (thrust) 9813.5)
    (= (touch-height) 1.5) (= (safe-speed) 1.5))
  (:goal (and (landed))))
