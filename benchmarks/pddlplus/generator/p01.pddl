(define (problem generator-01)
  (:domain generator)
  (:objects gen - generator t1 - tank)
  (:init
    (= (fuel gen) 25) (= (capacity gen) 26)
    (= (gen-duration) 54) (= (refuel-rate) 2)
    (= (tank-fuel t1) 30) (available t1))
  (:goal (and (generator-ran))))
